//! Scanner rules: canonical output, index and vertex errors with line numbers.

use super::*;

fn run(src: &str) -> Result<Scan, LoadError> {
    scan(Path::new("t.obj"), src)
}

#[test]
fn canonical_text_keeps_lines() {
    let s = run("v 0 0 0 0.5 0.5 0.5 # coloured\nv 2 0 0 2\n\tv 0 1 0\nvt 0.25\r\nf -3/1 2/1 3/-1\n  g  my group \n")
        .expect("valid");
    let lines: Vec<&str> = s.text.lines().collect();
    assert_eq!(
        lines,
        [
            "v 0 0 0",
            "v 1 0 0",
            "v 0 1 0",
            "vt 0.25 0",
            "f 1/1 2/1 3/1",
            "g my group"
        ]
    );
    assert_eq!(s.names.get("my group"), Some(&NameKind::Group));
    assert_eq!(s.triangles, 1);
}

#[test]
fn index_rules() {
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (face, kind) in [
        ("f 1 2 4", LoadErrorKind::IndexOutOfRange),
        ("f -1 -2 -4", LoadErrorKind::IndexOutOfRange),
        ("f 0 1 2", LoadErrorKind::IndexOutOfRange),
        ("f 1/1 2 3", LoadErrorKind::IndexOutOfRange),
        ("f -9223372036854775808 1 2", LoadErrorKind::IndexOutOfRange),
        ("f 99999999999999999999 1 2", LoadErrorKind::Parse),
        ("f 1/2/3/4 1 2", LoadErrorKind::Parse),
        ("f /1 1 2", LoadErrorKind::Parse),
        ("f 1.5 1 2", LoadErrorKind::Parse),
        ("f", LoadErrorKind::Parse),
    ] {
        let e = run(&format!("{tri}{face}\n")).expect_err(face);
        assert_eq!((e.kind, e.element.as_str()), (kind, "line 4"), "{face}");
    }
    let s = run(&format!("{tri}f 1 2\nl 1 2 3\np 1\n")).expect("ignored");
    assert_eq!(s.triangles, 0);
    assert_eq!(s.ignored.len(), 3);
}

#[test]
fn vertex_rules() {
    for (v, kind) in [
        ("v 1 2", LoadErrorKind::Parse),
        ("v 1 2 3 4 5", LoadErrorKind::Parse),
        ("v 1 2 3 0", LoadErrorKind::Parse),
        ("v 1 2 3 r g b", LoadErrorKind::Parse),
        ("v 1e39 0 0", LoadErrorKind::NonFinite),
        ("v 1 -inf 0", LoadErrorKind::NonFinite),
        ("v 1 1 1 1e-45", LoadErrorKind::NonFinite),
        ("vn 0 1", LoadErrorKind::Parse),
        ("vt", LoadErrorKind::Parse),
    ] {
        let e = run(&format!("# c\n{v}\n")).expect_err(v);
        assert_eq!((e.kind, e.element.as_str()), (kind, "line 2"), "{v}");
    }
}

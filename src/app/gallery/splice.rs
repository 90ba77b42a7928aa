//! A partial gallery run (`--only`) into a directory that already has a page: the new
//! sections replace the old ones of the same entries, every other section stays, so
//! re-rendering a few entries does not drop the rest of the gallery.
//!
//! A page is a header (everything before the first `## ` line) and sections, each from its
//! `## NAME` line to the next. The spliced page keeps the old header and lists the sections
//! in the order `names` gives (the gallery's entry order); sections whose title is not in
//! `names` follow, in the old page's order.

/// The header and the (title, text) sections of a page.
fn sections(page: &str) -> (&str, Vec<(&str, &str)>) {
    let mut starts: Vec<usize> = page.match_indices("\n## ").map(|(i, _)| i + 1).collect();
    if page.starts_with("## ") {
        starts.insert(0, 0);
    }
    let header = &page[..starts.first().copied().unwrap_or(page.len())];
    let mut out = Vec::new();
    for (k, &s) in starts.iter().enumerate() {
        let end = starts.get(k + 1).copied().unwrap_or(page.len());
        let text = &page[s..end];
        let title = text[3..].lines().next().unwrap_or("").trim();
        out.push((title, text));
    }
    (header, out)
}

/// `old` with the sections of `new` put in (see the module docs).
pub fn splice(old: &str, new: &str, names: &[&str]) -> String {
    let (header, old_sections) = sections(old);
    let (_, new_sections) = sections(new);
    let find = |title: &str| {
        new_sections
            .iter()
            .chain(old_sections.iter())
            .find(|(t, _)| *t == title)
            .map(|(_, text)| *text)
    };
    let mut out = header.to_string();
    // Each section ends in one blank line; the page in one newline.
    let mut push = |text: &str| {
        out.push_str(text.trim_end());
        out.push_str("\n\n");
    };
    for name in names {
        if let Some(text) = find(name) {
            push(text);
        }
    }
    for (title, text) in &old_sections {
        if !names.contains(title) {
            push(text);
        }
    }
    let end = out.trim_end().len();
    out.truncate(end);
    out.push('\n');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_sections_replace_old_ones_and_the_rest_stays_in_order() {
        let old = "# G\n\nold header\n\n## a\n\nA1\n\n## b\n\nB1\n\n## z\n\nZ1\n";
        let new = "# G\n\nnew header\n\n## b\n\nB2\n\n## c\n\nC2\n";
        let page = splice(old, new, &["a", "b", "c"]);
        assert_eq!(
            page,
            "# G\n\nold header\n\n## a\n\nA1\n\n## b\n\nB2\n\n## c\n\nC2\n\n## z\n\nZ1\n"
        );
    }

    #[test]
    fn a_page_without_sections_takes_the_new_ones() {
        let page = splice("# G\n", "# G\n\n## a\n\nA\n", &["a"]);
        assert_eq!(page, "# G\n## a\n\nA\n");
    }
}

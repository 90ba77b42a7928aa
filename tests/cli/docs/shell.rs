//! Reading a command line as a shell would, for `tests/cli/docs/mod.rs`: words, quotes, variables,
//! comments and the operators between simple commands; which of them run `iris`.

/// One shell word: its text after quotes and variables, and the inside of its quotes when
/// the whole word is one quoted string.
pub struct Word {
    pub text: String,
    pub quoted: Option<String>,
}

/// Splits a line as a shell would, into simple commands of words (the rule is in
/// `tests/cli/docs/mod.rs`).
pub fn shell_commands(line: &str) -> Vec<Vec<Word>> {
    let mut commands = vec![Vec::new()];
    let mut word: Option<Word> = None;
    let mut chars = line.chars().peekable();
    let variable = |chars: &mut std::iter::Peekable<std::str::Chars>| {
        let braced = chars.next_if_eq(&'{').is_some();
        while chars
            .next_if(|c| c.is_alphanumeric() || *c == '_')
            .is_some()
        {}
        if braced {
            chars.next_if_eq(&'}');
        }
        "1"
    };
    while let Some(c) = chars.next() {
        let w = word.get_or_insert_with(|| Word {
            text: String::new(),
            quoted: None,
        });
        let fresh = w.text.is_empty() && w.quoted.is_none();
        match c {
            ' ' | '\t' => {
                if !fresh {
                    commands
                        .last_mut()
                        .expect("one")
                        .push(word.take().expect("word"));
                }
            }
            '#' if fresh => break,
            ';' | '&' | '|' => {
                if !fresh {
                    commands
                        .last_mut()
                        .expect("one")
                        .push(word.take().expect("word"));
                }
                word = None;
                commands.push(Vec::new());
            }
            '\'' | '"' => {
                let mut inner = String::new();
                while let Some(q) = chars.next() {
                    match q {
                        _ if q == c => break,
                        '$' if c == '"' => inner.push_str(variable(&mut chars)),
                        _ => inner.push(q),
                    }
                }
                w.text.push_str(&inner);
                w.quoted = fresh.then_some(inner);
            }
            '\\' => w.text.extend(chars.next()),
            '$' if chars.peek().is_some_and(|c| c.is_alphabetic() || *c == '{') => {
                w.text.push_str(variable(&mut chars));
                w.quoted = None;
            }
            _ => {
                w.text.push(c);
                w.quoted = None;
            }
        }
    }
    if let Some(w) = word.filter(|w| !w.text.is_empty() || w.quoted.is_some()) {
        commands.last_mut().expect("one").push(w);
    }
    commands
}

/// The line without its `# comment` (a `#` starting a word outside quotes).
pub fn strip_comment(line: &str) -> &str {
    let mut quote = None;
    let mut prev = ' ';
    for (i, c) in line.char_indices() {
        match (quote, c) {
            (None, '\'' | '"') => quote = Some(c),
            (Some(q), _) if c == q => quote = None,
            (None, '#') if prev.is_whitespace() => return &line[..i],
            _ => {}
        }
        prev = c;
    }
    line
}

pub fn is_synopsis(line: &str) -> bool {
    let chars: Vec<char> = line.chars().collect();
    let alternative = chars
        .windows(3)
        .any(|w| w[1] == '|' && !w[0].is_whitespace() && !w[2].is_whitespace() && w[0] != '|');
    line.contains('[') || line.contains("...") || line.contains('…') || alternative
}

/// `iris ARGS`, `…/iris ARGS`, `scripts/run render ARGS`, `scripts/run iris ARGS` → ARGS
/// (after `iris`); anything else → None.
pub fn iris_args(words: &[String]) -> Option<Vec<String>> {
    let skip = words.iter().position(|w| {
        let assignment = w.split_once('=').is_some_and(|(name, _)| {
            !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        });
        !(assignment || matches!(w.as_str(), "do" | "then" | "else"))
    })?;
    let words = &words[skip..];
    match words {
        [head, rest @ ..] if head == "iris" || head.ends_with("/iris") => Some(rest.to_vec()),
        [run, sub, rest @ ..] if run == "scripts/run" && sub == "render" => Some(
            std::iter::once(sub.clone())
                .chain(rest.iter().cloned())
                .collect(),
        ),
        [run, sub, rest @ ..] if run == "scripts/run" && sub == "iris" => Some(rest.to_vec()),
        _ => None,
    }
}

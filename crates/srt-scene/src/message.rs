//! Messages a person can read: every error and warning srt-scene produces is one line of at most
//! [`MAX_MESSAGE_CHARS`] characters, whatever a file or a parser put into it.
//!
//! [`one_line`] is applied once, where messages leave the crate: the `Display` of
//! [`ImportError`](crate::import::ImportError) and [`SceneError`](crate::SceneError), and the
//! warnings of a loaded model or a built scene. [`quote`] is for echoing file content inside a
//! message (a line that does not parse, a word that is not a number): short and escaped.

/// The longest message, in characters (longer ones end in "…").
pub const MAX_MESSAGE_CHARS: usize = 300;

/// The longest piece of file content [`quote`] echoes, in characters.
pub const MAX_QUOTE_CHARS: usize = 40;

/// `text` as one line of at most [`MAX_MESSAGE_CHARS`] characters: see [`bounded`].
#[must_use]
pub fn one_line(text: &str) -> String {
    bounded(text, MAX_MESSAGE_CHARS)
}

/// `text` in double quotes, as one line of at most [`MAX_QUOTE_CHARS`] characters inside them:
/// see [`bounded`].
#[must_use]
pub fn quote(text: &str) -> String {
    format!("\"{}\"", bounded(text, MAX_QUOTE_CHARS))
}

/// The reason of an I/O error in words as the OS says it ("no such file or directory"), without
/// the "(os error N)" number or the " at path …" temporary-file names `tempfile` adds.
#[must_use]
pub fn io_reason(error: &std::io::Error) -> String {
    let text = error.to_string();
    let words = text
        .split(" (os error")
        .next()
        .and_then(|t| t.split(" at path ").next())
        .unwrap_or(&text);
    let mut chars = words.chars();
    chars.next().map_or_else(String::new, |first| {
        first.to_lowercase().chain(chars).collect()
    })
}

/// `text` as one printable line of at most `max_chars` characters (at least 1): every run of
/// whitespace (newlines and tabs included) becomes one space, control and invisible formatting
/// characters (and U+FFFD, which stands for bytes that were not text) are written as escapes
/// such as `\x00` or `\u{202e}`, leading and trailing space is dropped, and a text that is
/// still too long is cut and ends in "…".
#[must_use]
pub fn bounded(text: &str, max_chars: usize) -> String {
    let max_chars = max_chars.max(1);
    let mut out = String::new();
    let mut count = 0;
    let mut pending_space = false;
    let mut piece = String::new();
    for c in text.chars() {
        if c.is_whitespace() {
            pending_space = count > 0;
            continue;
        }
        piece.clear();
        if pending_space {
            piece.push(' ');
            pending_space = false;
        }
        let escaped = needs_escape(c);
        if escaped {
            let code = u32::from(c);
            if code < 0x100 {
                piece.push_str(&format!("\\x{code:02x}"));
            } else {
                piece.push_str(&format!("\\u{{{code:x}}}"));
            }
        } else {
            piece.push(c);
        }
        let piece_chars = piece.chars().count();
        if count + piece_chars > max_chars {
            // Keep room for the ellipsis.
            while count >= max_chars {
                out.pop();
                count -= 1;
            }
            if !escaped {
                out.extend(piece.chars().take(max_chars - 1 - count));
            }
            out.push('…');
            return out;
        }
        out.push_str(&piece);
        count += piece_chars;
    }
    out
}

/// Characters a terminal would not show as themselves: control characters, zero-width and
/// bidirectional formatting characters, the byte-order mark and replacement characters.
fn needs_escape(c: char) -> bool {
    c.is_control()
        || matches!(
            c,
            '\u{200b}'..='\u{200f}'
                | '\u{202a}'..='\u{202e}'
                | '\u{2060}'..='\u{206f}'
                | '\u{feff}'
                | '\u{fff9}'..='\u{fffd}'
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whitespace_collapses_to_one_line() {
        assert_eq!(bounded("  a\n\tb \r\n c  ", 100), "a b c");
        assert_eq!(bounded("", 10), "");
    }

    #[test]
    fn non_printables_are_escaped() {
        assert_eq!(bounded("a\0b\x1b[31m", 100), "a\\x00b\\x1b[31m");
        assert_eq!(bounded("x\u{202e}y\u{fffd}", 100), "x\\u{202e}y\\u{fffd}");
        assert_eq!(bounded("\u{7f}", 100), "\\x7f");
    }

    #[test]
    fn long_text_is_cut_with_an_ellipsis() {
        let long = "word ".repeat(1000);
        let cut = one_line(&long);
        assert_eq!(cut.chars().count(), MAX_MESSAGE_CHARS);
        assert!(cut.ends_with('…'));
        assert_eq!(bounded("abcdef", 4), "abc…");
        assert_eq!(bounded("abcd", 4), "abcd");
        // An escape is never cut in half.
        assert_eq!(bounded("ab\0", 4), "ab…");
        assert_eq!(quote(&"x".repeat(100)).chars().count(), MAX_QUOTE_CHARS + 2);
    }
}

//! Text leaving the program, escaped for where it goes: one function per target.
//!
//! A scene's title, its names and its path are the user's text, and may hold anything TOML
//! allows: `<!--<script>`, an ESC sequence, a newline. Every writer passes such text through
//! the function of its target, so that it is shown, never obeyed:
//!
//! - [`xml`] (also [`html`]): SVG and HTML text and attribute values;
//! - [`script_json`]: JSON placed inside an HTML `<script>` element;
//! - [`terminal`] and [`Terminal`]: text printed to a terminal;
//! - [`rust_comment`]: text inside a `//` comment of generated Rust.
//!
//! A control character (other than tab and newline, where the target allows them) is shown
//! as `\u{1b}`, the way Rust writes it.
//!
//! ```
//! use mechdiff::escape;
//! assert_eq!(escape::xml("a<b & \u{1b}"), "a&lt;b &amp; \\u{1b}");
//! assert_eq!(escape::script_json(r#"{"n":"<!--<script>"}"#), r#"{"n":"\u003c!--\u003cscript\u003e"}"#);
//! assert_eq!(escape::terminal("\u{1b}[31mred"), "\\u{1b}[31mred");
//! assert_eq!(escape::rust_comment("a\nfn evil() {}"), "a\\u{a}fn evil() {}");
//! ```

use std::borrow::Cow;
use std::fmt::Write as _;
use std::io::{self, Write};

/// Whether `c` is a control character a reader would obey rather than show: C0 (but tab and
/// newline, which `keep_lines` keeps), DEL and C1.
fn obeyed(c: char, keep_lines: bool) -> bool {
    c.is_control() && !(keep_lines && matches!(c, '\t' | '\n'))
}

/// `text` with every control character `obeyed` shown as `\u{..}` and `special` characters
/// replaced by `special`'s answer.
fn replace<'a>(
    text: &'a str,
    keep_lines: bool,
    special: impl Fn(char) -> Option<&'static str>,
) -> Cow<'a, str> {
    if !text
        .chars()
        .any(|c| obeyed(c, keep_lines) || special(c).is_some())
    {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 16);
    for c in text.chars() {
        match special(c) {
            Some(s) => out.push_str(s),
            None if obeyed(c, keep_lines) => {
                let _ = write!(out, "\\u{{{:x}}}", c as u32);
            }
            None => out.push(c),
        }
    }
    Cow::Owned(out)
}

/// Text for an SVG or XML document (text or a quoted attribute value): `& < > " '` as
/// entities, and the control characters XML 1.0 does not allow (and C1, DEL) shown as
/// `\u{..}`, so the document stays well-formed. Tab and newline are kept.
pub fn xml(text: &str) -> Cow<'_, str> {
    replace(text, true, |c| match c {
        '&' => Some("&amp;"),
        '<' => Some("&lt;"),
        '>' => Some("&gt;"),
        '"' => Some("&quot;"),
        '\'' => Some("&#39;"),
        _ => None,
    })
}

/// Text for an HTML page (text or a quoted attribute value): the same as [`xml`].
pub fn html(text: &str) -> Cow<'_, str> {
    xml(text)
}

/// JSON text placed inside an HTML `<script>` element: every `<` written `\u003c` (and
/// `>`, `&` and the JavaScript line separators U+2028, U+2029 as `\u` escapes too), so no
/// `<!--`, `<script` or `</script` can end or change the element. Outside strings JSON has
/// none of these characters, so the result is the same JSON value.
pub fn script_json(json: &str) -> Cow<'_, str> {
    if !json.contains(['<', '>', '&', '\u{2028}', '\u{2029}']) {
        return Cow::Borrowed(json);
    }
    let mut out = String::with_capacity(json.len() + 16);
    for c in json.chars() {
        match c {
            '<' => out.push_str("\\u003c"),
            '>' => out.push_str("\\u003e"),
            '&' => out.push_str("\\u0026"),
            '\u{2028}' => out.push_str("\\u2028"),
            '\u{2029}' => out.push_str("\\u2029"),
            c => out.push(c),
        }
    }
    Cow::Owned(out)
}

/// Control characters shown as `\u{..}` (tab and newline kept): the rule every target
/// shares, alone. For a document whose markup is escaped already but whose text may hold
/// control characters (plotters escapes `& < > " '` in an SVG, not these).
pub fn controls(text: &str) -> Cow<'_, str> {
    replace(text, true, |_| None)
}

/// Text printed to a terminal: ESC and every other control character shown as `\u{..}`
/// (tab and newline kept), so a title cannot move the cursor, recolour or retitle the
/// terminal.
pub fn terminal(text: &str) -> Cow<'_, str> {
    controls(text)
}

/// Text inside a `//` comment of generated Rust: newline, carriage return and every other
/// control character shown as `\u{..}`, so the text stays on the comment's line and cannot
/// add a line of code.
pub fn rust_comment(text: &str) -> Cow<'_, str> {
    replace(text, false, |_| None)
}

/// A writer for a terminal: the bytes pass through [`terminal`]'s rule as they are written
/// (ESC, the other C0 controls but tab and newline, DEL, and C1 controls written in UTF-8
/// are shown as `\u{..}`). The table, the reports and every message printed by the
/// `mechdiff` tool go through it.
#[derive(Debug)]
pub struct Terminal<W: Write> {
    inner: W,
    /// The last byte written was 0xC2, the lead byte of a C1 control (U+0080..U+009F) or of
    /// another character: decided with the next byte.
    pending_c2: bool,
}

impl<W: Write> Terminal<W> {
    /// Wraps `inner`.
    pub fn new(inner: W) -> Self {
        Terminal {
            inner,
            pending_c2: false,
        }
    }
}

/// The index of the first byte of `bytes` that [`Terminal`] must look at: a control
/// (but tab and newline), DEL, or 0xC2 (the lead byte of a C1 control). The bytes are tested
/// 32 at a time without an early exit (a loop the compiler turns into vector instructions):
/// a table of numbers passes at a few instructions per 32 bytes.
fn next_special(bytes: &[u8]) -> Option<usize> {
    let special = |b: u8| (b < 0x20 && b != b'\t' && b != b'\n') || b == 0x7f || b == 0xc2;
    let mut chunks = bytes.chunks_exact(32);
    let mut offset = 0;
    for chunk in &mut chunks {
        if chunk.iter().fold(false, |any, &b| any | special(b)) {
            return chunk.iter().position(|&b| special(b)).map(|k| offset + k);
        }
        offset += 32;
    }
    let rest = chunks.remainder().iter().position(|&b| special(b));
    rest.map(|k| offset + k)
}

impl<W: Write> Write for Terminal<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let Some(&first) = buf.first() else {
            return Ok(0);
        };
        let (mut start, mut i) = (0, 0);
        if std::mem::take(&mut self.pending_c2) {
            if (0x80..0xa0).contains(&first) {
                write!(self.inner, "\\u{{{first:x}}}")?;
                (start, i) = (1, 1);
            } else {
                self.inner.write_all(&[0xc2])?;
            }
        }
        while i < buf.len() {
            match next_special(&buf[i..]) {
                Some(skip) => i += skip,
                None => break,
            }
            let b = buf[i];
            let control = (b < 0x20 && b != b'\t' && b != b'\n') || b == 0x7f;
            if control {
                self.inner.write_all(&buf[start..i])?;
                write!(self.inner, "\\u{{{b:x}}}")?;
                start = i + 1;
            } else if b == 0xc2 {
                match buf.get(i + 1) {
                    Some(&next) if (0x80..0xa0).contains(&next) => {
                        self.inner.write_all(&buf[start..i])?;
                        write!(self.inner, "\\u{{{next:x}}}")?;
                        i += 1;
                        start = i + 1;
                    }
                    Some(_) => {}
                    None => {
                        self.inner.write_all(&buf[start..i])?;
                        self.pending_c2 = true;
                        return Ok(buf.len());
                    }
                }
            }
            i += 1;
        }
        self.inner.write_all(&buf[start..])?;
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        if std::mem::take(&mut self.pending_c2) {
            self.inner.write_all(&[0xc2])?;
        }
        self.inner.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn through_terminal(chunks: &[&[u8]]) -> String {
        let mut out = Terminal::new(Vec::new());
        for chunk in chunks {
            out.write_all(chunk).unwrap();
        }
        out.flush().unwrap();
        String::from_utf8(out.inner).unwrap()
    }

    #[test]
    fn the_terminal_writer_shows_controls_whatever_the_chunks() {
        let text = "a\u{1b}[2J\tb\n\u{9b}31m é\u{7f}";
        let expected = "a\\u{1b}[2J\tb\n\\u{9b}31m é\\u{7f}";
        assert_eq!(terminal(text), expected);
        assert_eq!(through_terminal(&[text.as_bytes()]), expected);
        // Split after every byte: a C1 control or an é cut in two is still decided right.
        let bytes: Vec<&[u8]> = text.as_bytes().chunks(1).collect();
        assert_eq!(through_terminal(&bytes), expected);
    }

    proptest::proptest! {
        /// Long texts of numbers, controls, C1 controls and other characters, split at
        /// random: the bytes the terminal writer passes over 32 at a time are escaped as
        /// [`terminal`] escapes the whole text.
        #[test]
        fn long_texts_are_escaped_whatever_the_chunks(
            text in "([0-9e. -]{0,40}[\\x00-\\x1f\\x7f\\u{80}-\\u{a0}é\n\t]?){0,12}",
            split in 1usize..80,
        ) {
            let bytes: Vec<&[u8]> = text.as_bytes().chunks(split).collect();
            proptest::prop_assert_eq!(through_terminal(&bytes), terminal(&text).into_owned());
        }
    }

    #[test]
    fn plain_text_is_borrowed_unchanged() {
        assert!(matches!(xml("φ = 30°, l1"), Cow::Borrowed(_)));
        assert!(matches!(terminal("a\tb\n"), Cow::Borrowed(_)));
        assert!(matches!(script_json(r#"{"a":[1,2]}"#), Cow::Borrowed(_)));
    }

    #[test]
    fn comments_keep_to_one_line() {
        assert_eq!(rust_comment("s\r\n*/ x"), "s\\u{d}\\u{a}*/ x");
    }
}

//! Where a value sits in JSON text, so that an error about its content (a parameter that is not
//! finite, a curve that is not a list of pairs) names its line and column as a syntax error
//! does.
//!
//! `serde_json::Value` keeps no positions, so [`locate`] scans the text again for the key path
//! of the value an error is about. The text has already been parsed (by
//! [`unique_keys`](super::unique_keys)), so the scan only has to find its way, not to check.
//!
//! ```
//! use hyst::data::json_place::{locate, JsonFile};
//! use std::path::Path;
//! let text = "{\n  \"primary\": {\n    \"positive\": [[0, 0], [1, \"x\"]]\n  }\n}";
//! assert_eq!(locate(text, &["primary", "positive", "1"]), Some((3, 26)));
//! let file = JsonFile::new(Path::new("t.json"), Some(text));
//! assert_eq!(file.at(&["primary", "positive"]), "t.json:3:17");
//! assert_eq!(file.at(&["nothing", "here"]), "t.json");
//! ```

use std::path::Path;

/// A JSON file's name and, where known, its text: what an error names as its place.
#[derive(Clone, Copy, Debug)]
pub struct JsonFile<'a> {
    path: &'a Path,
    text: Option<&'a str>,
}

impl<'a> JsonFile<'a> {
    /// The file at `path`, with its text if the caller has it (a value built in memory has
    /// none, and its errors name the file alone).
    pub fn new(path: &'a Path, text: Option<&'a str>) -> Self {
        JsonFile { path, text }
    }

    /// The file's path.
    pub fn path(&self) -> &'a Path {
        self.path
    }

    /// `path:line:column` of the value at the key path `keys` (array elements by their index
    /// as a string), or the file's path alone where the text is unknown or has no such value.
    pub fn at(&self, keys: &[&str]) -> String {
        match self.text.and_then(|t| locate(t, keys)) {
            Some((line, column)) => format!("{}:{line}:{column}", self.path.display()),
            None => self.path.display().to_string(),
        }
    }
}

/// Line and column (both from 1; the column in bytes, as serde_json counts it in syntax errors)
/// where the value at the key path `keys` starts in the JSON `text`; `None` if the text has no
/// such value or is not JSON.
pub fn locate(text: &str, keys: &[&str]) -> Option<(usize, usize)> {
    let mut scan = Scan {
        text,
        bytes: text.as_bytes(),
        at: 0,
    };
    let start = scan.find(keys)?;
    let before = &text[..start];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, str::len) + 1;
    Some((line, column))
}

struct Scan<'a> {
    text: &'a str,
    bytes: &'a [u8],
    at: usize,
}

impl Scan<'_> {
    fn peek(&self) -> Option<u8> {
        self.bytes.get(self.at).copied()
    }

    fn space(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t' | b'\n' | b'\r')) {
            self.at += 1;
        }
    }

    /// Moves past `byte` (after white space), or fails.
    fn expect(&mut self, byte: u8) -> Option<()> {
        self.space();
        (self.peek() == Some(byte)).then(|| self.at += 1)
    }

    /// The string starting here, decoded, and the scan past it.
    fn string(&mut self) -> Option<String> {
        let start = self.at;
        if self.peek() != Some(b'"') {
            return None;
        }
        self.at += 1;
        loop {
            match self.peek()? {
                b'\\' => self.at += 2,
                b'"' => break,
                _ => self.at += 1,
            }
        }
        self.at += 1;
        serde_json::from_str(self.text.get(start..self.at)?).ok()
    }

    /// Moves past the value starting here.
    fn skip(&mut self) -> Option<()> {
        self.space();
        match self.peek()? {
            b'"' => self.string().map(drop),
            open @ (b'{' | b'[') => {
                let close = if open == b'{' { b'}' } else { b']' };
                self.at += 1;
                self.space();
                if self.peek() == Some(close) {
                    self.at += 1;
                    return Some(());
                }
                loop {
                    if open == b'{' {
                        self.space();
                        self.string()?;
                        self.expect(b':')?;
                    }
                    self.skip()?;
                    self.space();
                    match self.peek()? {
                        b',' => self.at += 1,
                        c if c == close => {
                            self.at += 1;
                            return Some(());
                        }
                        _ => return None,
                    }
                }
            }
            _ => {
                while !matches!(
                    self.peek(),
                    None | Some(b',' | b'}' | b']' | b' ' | b'\t' | b'\n' | b'\r')
                ) {
                    self.at += 1;
                }
                Some(())
            }
        }
    }

    /// The byte offset of the value at `keys` below the value starting here.
    fn find(&mut self, keys: &[&str]) -> Option<usize> {
        self.space();
        let Some((first, rest)) = keys.split_first() else {
            return Some(self.at);
        };
        match self.peek()? {
            b'{' => {
                self.at += 1;
                loop {
                    self.space();
                    let key = self.string()?;
                    self.expect(b':')?;
                    if key == *first {
                        return self.find(rest);
                    }
                    self.skip()?;
                    self.expect(b',')?;
                }
            }
            b'[' => {
                let index: usize = first.parse().ok()?;
                self.at += 1;
                for _ in 0..index {
                    self.skip()?;
                    self.expect(b',')?;
                }
                self.space();
                if self.peek() == Some(b']') {
                    return None;
                }
                self.find(rest)
            }
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every value of a nested document is found where it starts, by keys and by indices,
    /// past strings holding the characters the scan steers by.
    #[test]
    fn values_are_found_where_they_start() {
        let text = "{\"a\": \"x,}]\\\"{\", \"b\" : [1, {\"c\": [true, null]}, -2.5e3],\n\t\"d\": {}, \"é\": {\"k\": []}}";
        let cases: [(&[&str], &str); 8] = [
            (&["a"], "\"x,}]"),
            (&["b"], "[1, {"),
            (&["b", "0"], "1, {"),
            (&["b", "1", "c"], "[true"),
            (&["b", "1", "c", "1"], "null"),
            (&["b", "2"], "-2.5e3"),
            (&["d"], "{}, "),
            (&["é", "k"], "[]}}"),
        ];
        for (keys, starts) in cases {
            let (line, column) = locate(text, keys).unwrap_or_else(|| panic!("{keys:?}"));
            let rest = &text.lines().nth(line - 1).expect("line")[column - 1..];
            assert!(rest.starts_with(starts), "{keys:?}: {rest}");
        }
        assert_eq!(locate(text, &["d"]), Some((2, 7)));
        for missing in [
            &["z"][..],
            &["b", "3"],
            &["a", "0"],
            &["b", "x"],
            &["d", "e"],
        ] {
            assert_eq!(locate(text, missing), None, "{missing:?}");
        }
        assert_eq!(locate("{\"a\": ", &["a", "b"]), None);
        assert_eq!(locate("[1, 2", &["5"]), None);
        assert_eq!(locate("{\"a\": []}", &["a", "0"]), None);
        assert_eq!(locate("{\"a\": [5 ]}", &["a", "1"]), None);
        // Columns count bytes, as serde_json's syntax errors do: "é" is two.
        assert_eq!(locate("{\"é\": 1}", &["é"]), Some((1, 8)));
    }
}

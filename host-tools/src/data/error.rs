//! The error of the readers: where (file, line, column) and what was expected.

use std::fmt;
use std::path::{Path, PathBuf};

/// Where in a file something was found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Location {
    /// The file as a whole (it could not be opened, or an option does not fit it).
    File,
    /// A line and a column (field), both 1-based: `file:17:2`.
    Text {
        /// Line number, 1-based, counting every line of the file.
        line: usize,
        /// Field number, 1-based (`1` when the whole line is meant).
        column: usize,
    },
    /// A place in a JSON document, as a path from the root such as
    /// `data.force[17]` (JSON values carry no line numbers once parsed).
    Json(String),
}

/// A reading error: the file, the place in it, and a message saying what was
/// expected and what was found.
///
/// Its `Display` is `file:line:column: message`, e.g.
/// `spd_369.csv:17:2: expected a number for column 'force_kN', found 'abc'`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DataError {
    file: PathBuf,
    location: Location,
    message: String,
}

impl DataError {
    /// An error at a line and column (both 1-based).
    pub fn at(file: &Path, line: usize, column: usize, message: impl Into<String>) -> Self {
        DataError {
            file: file.to_path_buf(),
            location: Location::Text { line, column },
            message: visible(message.into()),
        }
    }

    /// An error about the file as a whole.
    pub fn file(file: &Path, message: impl Into<String>) -> Self {
        DataError {
            file: file.to_path_buf(),
            location: Location::File,
            message: visible(message.into()),
        }
    }

    /// An error at a place in a JSON document.
    pub fn json(file: &Path, path: impl Into<String>, message: impl Into<String>) -> Self {
        DataError {
            file: file.to_path_buf(),
            location: Location::Json(visible(path.into())),
            message: visible(message.into()),
        }
    }

    /// The file the error is about.
    pub fn path(&self) -> &Path {
        &self.file
    }

    /// Where in the file.
    pub fn location(&self) -> &Location {
        &self.location
    }

    /// What was expected and what was found.
    pub fn message(&self) -> &str {
        &self.message
    }
}

/// `text` with the characters a terminal does not show written as escapes
/// (`\u{0}`, `\u{feff}`): control characters, byte-order marks and
/// zero-width characters. A message echoes what it found, and a NUL or a
/// byte-order mark in the middle of a file used to be printed raw: "found
/// '1.0'" for a field that is not "1.0" (found by review).
fn visible(text: String) -> String {
    let hidden =
        |c: char| c.is_control() || matches!(c, '\u{200b}'..='\u{200f}' | '\u{2060}' | '\u{feff}');
    if !text.chars().any(hidden) {
        return text;
    }
    text.chars()
        .map(|c| {
            if hidden(c) {
                format!("\\u{{{:x}}}", c as u32)
            } else {
                c.to_string()
            }
        })
        .collect()
}

impl fmt::Display for DataError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let file = self.file.display();
        match &self.location {
            Location::File => write!(f, "{file}: {}", self.message),
            Location::Text { line, column } => {
                write!(f, "{file}:{line}:{column}: {}", self.message)
            }
            Location::Json(path) => write!(f, "{file}: at {path}: {}", self.message),
        }
    }
}

impl std::error::Error for DataError {}

//! JSON text whose objects name each key once.
//!
//! `serde_json` keeps the last of two equal keys, so `{"k0": 6, ..., "k0": 60}` would be read
//! as `k0 = 60` without a word. Every JSON file `hyst` reads (parameter files, PHM files, JSON
//! records) goes through [`parse`], which refuses a repeated key with its line and column.
//!
//! ```
//! let e = hyst::data::unique_keys::parse(r#"{"k0": 6,
//!   "k0": 60}"#).unwrap_err();
//! assert_eq!((e.line(), e.to_string()), (2, "key 'k0' given twice in one object at line 2 column 6".into()));
//! ```

use serde::de::{self, Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Value};
use std::fmt;
use std::path::Path;

/// Parses `text` as one JSON value, refusing an object that names a key twice.
pub fn parse(text: &str) -> Result<Value, serde_json::Error> {
    serde_json::from_str::<Unique>(text).map(|u| u.0)
}

/// [`parse`] for the text of the file at `path`, its error as `path:line:column: not valid
/// JSON: ...`.
pub fn parse_file(path: &Path, text: &str) -> anyhow::Result<Value> {
    parse(text).map_err(|e| {
        anyhow::anyhow!(
            "{}:{}:{}: not valid JSON: {e}",
            path.display(),
            e.line(),
            // serde_json counts an error before the first character (an
            // empty file) as column 0; columns are counted from 1.
            e.column().max(1)
        )
    })
}

/// A JSON value built by [`UniqueVisitor`].
struct Unique(Value);

impl<'de> Deserialize<'de> for Unique {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(UniqueVisitor).map(Unique)
    }
}

struct UniqueVisitor;

impl<'de> Visitor<'de> for UniqueVisitor {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Bool(v))
    }
    fn visit_i64<E>(self, v: i64) -> Result<Value, E> {
        Ok(v.into())
    }
    fn visit_u64<E>(self, v: u64) -> Result<Value, E> {
        Ok(v.into())
    }
    fn visit_f64<E>(self, v: f64) -> Result<Value, E> {
        Ok(v.into())
    }
    fn visit_str<E>(self, v: &str) -> Result<Value, E> {
        Ok(Value::String(v.to_owned()))
    }
    fn visit_string<E>(self, v: String) -> Result<Value, E> {
        Ok(Value::String(v))
    }
    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut items = Vec::new();
        while let Some(Unique(v)) = seq.next_element()? {
            items.push(v);
        }
        Ok(Value::Array(items))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut object = Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if object.contains_key(&key) {
                return Err(de::Error::custom(format!(
                    "key '{key}' given twice in one object"
                )));
            }
            let Unique(value) = map.next_value()?;
            object.insert(key, value);
        }
        Ok(Value::Object(object))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same documents as `serde_json` reads them, nested objects and arrays included.
    #[test]
    fn documents_without_repeats_read_as_serde_json_reads_them() {
        for text in [
            r#"{"a": 1, "b": [1.5, -2, "x", null, true, {"a": 2}], "c": {"d": {}}}"#,
            "[]",
            "3.25",
            r#""text""#,
        ] {
            assert_eq!(
                parse(text).unwrap(),
                serde_json::from_str::<Value>(text).unwrap()
            );
        }
    }

    /// A repeat is refused at any depth; equal keys in different objects are not repeats.
    #[test]
    fn a_repeated_key_is_refused_at_any_depth() {
        let e = parse(r#"{"data": {"disp": [1], "disp": [2]}}"#).unwrap_err();
        assert!(e.to_string().starts_with("key 'disp' given twice"), "{e}");
        assert!(parse(r#"[{"a": 1}, {"a": 2}]"#).is_ok());
    }

    /// Errors are placed at a line and a column counted from 1, also in an empty file.
    #[test]
    fn an_empty_file_is_placed_at_column_1() {
        let e = parse_file(Path::new("empty.json"), "").unwrap_err();
        assert!(
            e.to_string().starts_with("empty.json:1:1: not valid JSON"),
            "{e}"
        );
        let e = parse_file(Path::new("cut.json"), "{\"a\":").unwrap_err();
        assert!(
            e.to_string().starts_with("cut.json:1:5: not valid JSON"),
            "{e}"
        );
    }
}

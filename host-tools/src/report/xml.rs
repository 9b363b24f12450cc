//! Escaping text for XML and HTML (the five predefined entities).

use std::borrow::Cow;

/// `text` with `&`, `<`, `>`, `"` and `'` replaced by entities, safe both as
/// element content and inside a quoted attribute.
pub fn escape(text: &str) -> Cow<'_, str> {
    if !text.contains(['&', '<', '>', '"', '\'']) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 16);
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::escape;

    #[test]
    fn escapes_markup_and_quotes() {
        assert_eq!(
            escape(r#"<a href="x">B&W's</a>"#),
            "&lt;a href=&quot;x&quot;&gt;B&amp;W&#39;s&lt;/a&gt;"
        );
    }

    #[test]
    fn leaves_plain_text_borrowed() {
        assert!(matches!(
            escape("Force (kN) ±5 µm"),
            std::borrow::Cow::Borrowed(_)
        ));
    }
}

//! The bytes of a table as a file: the blob itself, a Rust `static` or a C
//! header.

use anyhow::{bail, Result};
use std::fmt::Write;

/// Output format of `hyst export`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// The table's bytes (for `include_bytes!` or a flash partition).
    Bin,
    /// A Rust source file with the table as a `static` byte array.
    Rust,
    /// A C header with the table as a `static const uint8_t` array.
    C,
}

fn hex_rows(out: &mut String, bytes: &[u8], indent: &str) {
    for row in bytes.chunks(16) {
        out.push_str(indent);
        let cells: Vec<String> = row.iter().map(|b| format!("0x{b:02x},")).collect();
        out.push_str(&cells.join(" "));
        out.push('\n');
    }
}

fn is_identifier(name: &str) -> bool {
    let mut chars = name.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Rust's strict and reserved keywords (2024 edition), which cannot name a static.
const RUST_KEYWORDS: &[&str] = &[
    "_", "abstract", "as", "async", "await", "become", "box", "break", "const", "continue",
    "crate", "do", "dyn", "else", "enum", "extern", "false", "final", "fn", "for", "gen", "if",
    "impl", "in", "let", "loop", "macro", "match", "mod", "move", "mut", "override", "priv", "pub",
    "ref", "return", "self", "Self", "static", "struct", "super", "trait", "true", "try", "type",
    "typeof", "unsafe", "unsized", "use", "virtual", "where", "while", "yield",
];

/// C's keywords (C23, with C11's spellings), which cannot name an array.
const C_KEYWORDS: &[&str] = &[
    "alignas",
    "alignof",
    "auto",
    "bool",
    "break",
    "case",
    "char",
    "const",
    "constexpr",
    "continue",
    "default",
    "do",
    "double",
    "else",
    "enum",
    "extern",
    "false",
    "float",
    "for",
    "goto",
    "if",
    "inline",
    "int",
    "long",
    "nullptr",
    "register",
    "restrict",
    "return",
    "short",
    "signed",
    "sizeof",
    "static",
    "static_assert",
    "struct",
    "switch",
    "thread_local",
    "true",
    "typedef",
    "typeof",
    "typeof_unqual",
    "union",
    "unsigned",
    "void",
    "volatile",
    "while",
    "_Alignas",
    "_Alignof",
    "_Atomic",
    "_BitInt",
    "_Bool",
    "_Complex",
    "_Decimal128",
    "_Decimal32",
    "_Decimal64",
    "_Generic",
    "_Imaginary",
    "_Noreturn",
    "_Static_assert",
    "_Thread_local",
];

/// Renders `bytes` in `format`. `name` is the Rust static's or C array's
/// name; `about` is a comment (provenance and contents, one line each).
pub fn render(bytes: &[u8], format: Format, name: &str, about: &[String]) -> Result<Vec<u8>> {
    if format != Format::Bin && !is_identifier(name) {
        bail!("--name {name:?} is not a valid identifier");
    }
    let (language, keywords) = match format {
        Format::Rust => ("Rust", RUST_KEYWORDS),
        Format::C => ("C", C_KEYWORDS),
        Format::Bin => ("", &[][..]),
    };
    if keywords.contains(&name) {
        bail!("--name {name:?} is a keyword of {language}: choose another name");
    }
    // Names a C program cannot define for itself, or that the header's own
    // `#include <stdint.h>` and include guard (`NAME_H`, upper case) break
    // (found by review: `main`, `NULL`, `uint8_t`, `INT8_MAX` and `_stdint`,
    // whose guard `_STDINT_H` is glibc's, were accepted).
    if format == Format::C {
        let upper = name.to_ascii_uppercase();
        let stdint_macro = [
            "INT",
            "UINT",
            "SIZE_",
            "PTRDIFF_",
            "SIG_ATOMIC_",
            "WCHAR_",
            "WINT_",
        ]
        .iter()
        .any(|p| upper.starts_with(p))
            && (upper.ends_with("_MAX") || upper.ends_with("_MIN") || upper.ends_with("_C"));
        let why = match name {
            "main" => Some("the program's entry point"),
            "NULL" => Some("a macro of the standard headers"),
            _ if name.starts_with('_') => Some(
                "reserved to the implementation (its include guard would begin with an underscore and a capital)",
            ),
            _ if name.ends_with("_t") => Some("a type name (`_t` names are reserved by POSIX and stdint.h)"),
            _ if stdint_macro => Some("a macro of stdint.h"),
            _ => None,
        };
        if let Some(why) = why {
            bail!("--name {name:?} is {why} in C: choose another name");
        }
    }
    let n = bytes.len();
    let mut s = String::new();
    match format {
        Format::Bin => return Ok(bytes.to_vec()),
        Format::Rust => {
            for line in about {
                let _ = writeln!(s, "// {line}");
            }
            let _ = writeln!(
                s,
                "\n/// The parameter table (format: `docs/table-format.md`). A `static`,\n\
                 /// so it lives once in flash and `BwbnTable::load(&{name})` /\n\
                 /// `PhmTable::load(&{name})` read it in place."
            );
            let _ = writeln!(s, "#[rustfmt::skip]\npub static {name}: [u8; {n}] = [");
            hex_rows(&mut s, bytes, "    ");
            s.push_str("];\n");
        }
        Format::C => {
            let guard = format!("{}_H", name.to_ascii_uppercase());
            s.push_str("/*\n");
            for line in about {
                let _ = writeln!(s, " * {line}");
            }
            s.push_str(" */\n");
            let _ = writeln!(
                s,
                "#ifndef {guard}\n#define {guard}\n\n#include <stdint.h>\n"
            );
            let _ = writeln!(s, "#define {}_LEN {n}u\n", name.to_ascii_uppercase());
            let _ = writeln!(
                s,
                "/* Format: docs/table-format.md. Verify magic, version, length and the\n   \
                 CRC-32 before using a value. */\nstatic const uint8_t {name}[{n}] = {{"
            );
            hex_rows(&mut s, bytes, "    ");
            let _ = writeln!(s, "}};\n\n#endif /* {guard} */");
        }
    }
    Ok(s.into_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sources_hold_the_bytes_sixteen_a_row() {
        let bytes: Vec<u8> = (0..20).collect();
        let r = String::from_utf8(render(&bytes, Format::Rust, "TABLE", &["x".into()]).unwrap())
            .unwrap();
        assert!(r.starts_with("// x\n"));
        assert!(r.contains("pub static TABLE: [u8; 20] = [\n    0x00, 0x01,"));
        assert!(r.contains("0x0f,\n    0x10, 0x11, 0x12, 0x13,\n];"));
        let c = String::from_utf8(render(&bytes, Format::C, "hyst_table", &[]).unwrap()).unwrap();
        assert!(c.contains("#define HYST_TABLE_LEN 20u"));
        assert!(c.contains("static const uint8_t hyst_table[20] = {\n    0x00,"));
        assert!(c.trim_end().ends_with("#endif /* HYST_TABLE_H */"));
        assert!(render(&bytes, Format::C, "2x", &[]).is_err());
        for reserved in [
            "main", "NULL", "__table", "_Table", "_stdint", "uint8_t", "INT8_MAX", "UINT64_C",
        ] {
            let e = render(&bytes, Format::C, reserved, &[])
                .unwrap_err()
                .to_string();
            assert!(e.contains(" in C: choose another name"), "{reserved}: {e}");
        }
        assert!(render(&bytes, Format::C, "table_2", &[]).is_ok());
        assert!(render(&bytes, Format::Rust, "main", &[]).is_ok());
        assert_eq!(render(&bytes, Format::Bin, "", &[]).unwrap(), bytes);
    }
}

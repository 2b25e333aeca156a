//! Errors of form (pass 2 of [`crate::Scene::parse_str`]): serde's message
//! and byte span turned into the field at fault, its line, and a message
//! in the user's words.
//!
//! serde speaks of Rust: "invalid type: integer `3`, expected internally
//! tagged enum ShapeSpec", "map", "sequence", "f64", "variant identifier",
//! "integer `…` as i128", and reads a TOML date as a map with the private
//! key `$__toml_private_datetime`. [`plain`] rewrites each part:
//! "expected a table with a `type`, found the integer 3".
//!
//! toml places the span of an error inside a table that serde buffers (the
//! tables tagged by `type`: shapes, forces, events) on the whole table, so
//! the field is found by [`culprit`]: each key of that table is tried alone
//! in a small document of the same shape, and the first whose value alone
//! fails is the field at fault.

use crate::error::{ErrorKind, FieldPath, SceneError, Segment};
use crate::format::SceneFile;
use crate::location::{key_below, line_column, path_at, position_of};
use toml::de::{DeTable, DeValue};

/// The private key under which toml hands a date-time to serde.
const DATETIME_KEY: &str = "$__toml_private_datetime";

/// Turns a serde error (a message and a byte span) into a located error in
/// plain words.
pub(crate) fn form_error(origin: &str, text: &str, error: &toml::de::Error) -> SceneError {
    let message = error.message();
    let kind = if message.starts_with("unknown field") && !message.contains(DATETIME_KEY) {
        ErrorKind::UnknownField
    } else if message.starts_with("missing field") {
        ErrorKind::MissingField
    } else {
        ErrorKind::InvalidType
    };
    let Some(span) = error.span() else {
        return SceneError::new(origin, kind, plain(message, None)).at(Some((1, 1)));
    };
    let mut path = path_at(text, span.clone());
    if path.0.last() == Some(&Segment::Key(DATETIME_KEY.into())) {
        path.0.pop();
    }
    let mut position = Some(line_column(text, span.start));
    // serde names an unknown or missing key in its message, but toml spans
    // a buffered table: append the key to the table's path.
    let named_key = match kind {
        ErrorKind::UnknownField | ErrorKind::MissingField => message.split('`').nth(1),
        _ => None,
    };
    if kind == ErrorKind::MissingField && named_key == Some("simulation") {
        // serde spans the first table it buffered (`bodies[0]`), but
        // `[simulation]` is a table of the file itself.
        return SceneError::new(
            origin,
            kind,
            "the file has no [simulation] table: add one with `dt` and `duration` (both required, in s)",
        )
        .with_field(Some("simulation".into()))
        .at(Some((1, 1)));
    }
    if let (ErrorKind::MissingField, Some(key)) = (kind, named_key)
        && let Some(sub) = sub_table_missing(text, &path, key)
    {
        // serde spans the whole joint; the key belongs to its motor or
        // spring, which lacks it.
        position = position_of(text, &sub).or(position);
        path = sub;
    }
    if let Some(key) = named_key {
        if path.0.last() != Some(&Segment::Key(key.to_owned())) {
            path = match kind {
                // The key may sit in an inline table of the buffered one
                // (`motor = { ... }` of a joint).
                ErrorKind::UnknownField => key_below(text, &path, key).unwrap_or(path.key(key)),
                _ => path.key(key),
            };
            if kind == ErrorKind::UnknownField {
                position = position_of(text, &path).or(position);
            }
        }
    }
    let mut message = message.to_owned();
    if message.starts_with("expected table, found ") {
        // `kind = { static = 1 }`: toml read the table as a name and its
        // key as the name's contents; the name is the field at fault.
        path.0.pop();
        position = position_of(text, &path).or(position);
        let field = (!path.0.is_empty()).then(|| path.to_string());
        return SceneError::new(origin, kind, "expected a name (a string), found a table")
            .with_field(field)
            .at(position);
    }
    if is_enum_message(&message) {
        // toml's own words for a name given as something else (`kind = 3`,
        // `model = {}`): the value at the span says what was found.
        let literal = text.get(span.clone()).unwrap_or("").trim();
        message = format!(
            "expected a name (a string), found {}",
            literal_words(literal)
        );
        let field = (!path.0.is_empty()).then(|| path.to_string());
        return SceneError::new(origin, kind, message)
            .with_field(field)
            .at(position);
    }
    if kind == ErrorKind::InvalidType {
        if let Some((key, probe_message)) = culprit(text, &path) {
            path = path.key(&key);
            position = position_of(text, &path).or(position);
            message = probe_message;
        }
    }
    let datetime = datetime_at(text, &path);
    if datetime.is_some() {
        position = position_of(text, &path).or(position);
        if message.contains(DATETIME_KEY) {
            // `simulation = 1979-05-27`: serde saw a map with the private
            // key where it wanted the table's own keys.
            message = format!("invalid type: date-time, expected {}", table_words(&path));
        }
        message = message.replace("invalid type: map", "invalid type: date-time");
    }
    let field = (!path.0.is_empty()).then(|| path.to_string());
    SceneError::new(origin, kind, plain(&message, datetime.as_deref()))
        .with_field(field)
        .at(position)
}

/// toml's messages when a name (a unit variant) is given as another kind
/// of value: a number, an array or a table.
fn is_enum_message(message: &str) -> bool {
    message == "wanted string or table"
        || message.starts_with("wanted exactly 1 element")
        || message == "expected empty table"
        || message == "expected empty array"
        || message.starts_with("expected table with exactly 1 entry")
}

/// A TOML literal (the text of a value) in words: "the integer 3", "the
/// number 1.5", "the boolean true", "an array", "a table".
pub(crate) fn literal_words(literal: &str) -> String {
    let first = literal.chars().next();
    match first {
        Some('[') => "an array".into(),
        Some('{') => "a table".into(),
        Some('"') | Some('\'') => format!("the string {literal}"),
        _ if literal == "true" || literal == "false" => format!("the boolean {literal}"),
        _ => {
            let plain = literal.replace('_', "");
            if plain.parse::<i64>().is_ok() {
                format!("the integer {plain}")
            } else if let Ok(v) = plain.parse::<f64>() {
                format!("the number {}", engine::error::readable(v))
            } else {
                format!("`{literal}`")
            }
        }
    }
}

/// The top-level sections' own form, checked before serde sees them: a
/// table written as an array of tables (`[[simulation]]`), or an element of
/// `bodies`, `forces` or `events` written as an array, would reach serde as
/// a sequence, which it reads positionally into the table's fields and
/// reports in Rust's terms at a field the user never wrote.
pub(crate) fn check_sections(
    origin: &str,
    text: &str,
    root: &toml::Spanned<DeTable<'_>>,
) -> Result<(), SceneError> {
    let at = |span: std::ops::Range<usize>| Some(line_column(text, span.start));
    for (key, value) in root.get_ref() {
        let name = key.get_ref().as_ref();
        let single = ["simulation", "contact", "linear_test"].contains(&name);
        let listed = ["bodies", "forces", "events"].contains(&name);
        match value.get_ref() {
            DeValue::Array(items) if single => {
                let tables = items
                    .iter()
                    .all(|v| matches!(v.get_ref(), DeValue::Table(_)));
                let found = if tables {
                    format!("an array of tables [[{name}]]: write [{name}], once")
                } else {
                    "an array".into()
                };
                return Err(SceneError::new(
                    origin,
                    ErrorKind::InvalidType,
                    format!("expected the table [{name}], found {found}"),
                )
                .with_field(Some(name.to_owned()))
                .at(at(value.span())));
            }
            DeValue::Array(items) if listed => {
                for (i, item) in items.iter().enumerate() {
                    if let DeValue::Array(_) = item.get_ref() {
                        return Err(SceneError::new(
                            origin,
                            ErrorKind::InvalidType,
                            "expected a table, found an array".to_owned(),
                        )
                        .with_field(Some(format!("{name}[{i}]")))
                        .at(at(item.span())));
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// What the table at `path` is, for "expected ...".
fn table_words(path: &FieldPath) -> String {
    match path.0.last() {
        Some(Segment::Key(key)) => format!("the table [{key}]"),
        _ => "a table".into(),
    }
}

/// The text of the date-time value at `path`, if that is what it holds.
fn datetime_at(text: &str, path: &FieldPath) -> Option<String> {
    let root = DeTable::parse(text).ok()?;
    let mut value: Option<&DeValue<'_>> = None;
    let mut table = Some(root.get_ref());
    for segment in &path.0 {
        let next = match (segment, table, value) {
            (Segment::Key(k), Some(t), _) => t
                .iter()
                .find(|(key, _)| key.get_ref().as_ref() == k.as_str())
                .map(|(_, v)| v.get_ref()),
            (Segment::Index(i), _, Some(DeValue::Array(a))) => a.get(*i).map(|v| v.get_ref()),
            _ => None,
        };
        value = Some(next?);
        table = match value {
            Some(DeValue::Table(t)) => Some(t),
            _ => None,
        };
    }
    match value {
        Some(DeValue::Datetime(d)) => Some(d.to_string()),
        _ => None,
    }
}

/// The first key of the table at `path` whose value alone fails to
/// deserialize, with serde's message for it. Only for the tables of an
/// array of tables (`forces[2]`) and the inline tables they hold
/// (`bodies[0].shape`), the two places where serde buffers.
fn culprit(text: &str, path: &FieldPath) -> Option<(String, String)> {
    let (head, inline) = match path.0.as_slice() {
        [Segment::Key(array), Segment::Index(_)] => (format!("[[{array}]]\n"), None),
        [Segment::Key(array), Segment::Index(_), Segment::Key(key)] => {
            (format!("[[{array}]]\n"), Some(key.clone()))
        }
        _ => return None,
    };
    let root = DeTable::parse(text).ok()?;
    let table = table_at(root.get_ref(), path)?;
    let source = |v: &toml::Spanned<DeValue<'_>>| text.get(v.span()).map(str::to_owned);
    let tag = table
        .iter()
        .find(|(k, _)| k.get_ref().as_ref() == "type")
        .and_then(|(_, v)| source(v));
    for (key, value) in table.iter() {
        let key = key.get_ref().as_ref();
        if key == "type" {
            continue;
        }
        let Some(value_text) = source(value) else {
            continue;
        };
        let mut pairs = Vec::new();
        if let Some(tag) = &tag {
            pairs.push(format!("type = {tag}"));
        }
        pairs.push(format!("{} = {value_text}", quoted_key(key)));
        let probe = match &inline {
            None => format!("{head}{}\n", pairs.join("\n")),
            Some(field) => format!("{head}{} = {{ {} }}\n", quoted_key(field), pairs.join(", ")),
        };
        if let Err(e) = toml::from_str::<SceneFile>(&probe) {
            let m = e.message();
            let about_other_keys = m.starts_with("missing field") || m.starts_with("unknown field");
            if !about_other_keys && DeTable::parse(&probe).is_ok() {
                return Some((key.to_owned(), m.to_owned()));
            }
        }
    }
    None
}

fn quoted_key(key: &str) -> String {
    if !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        key.to_owned()
    } else {
        format!("\"{}\"", key.escape_default())
    }
}

/// The inline table of the table at `path` that lacks the required `key`
/// of its kind: a joint's `motor` (`max_torque`, `max_force`) or one of
/// its springs (`hertz`). `None` when the key is not such a key or no
/// such table lacks it (the key is then the table's own).
fn sub_table_missing(text: &str, path: &FieldPath, key: &str) -> Option<FieldPath> {
    let owners: &[&str] = match key {
        "max_torque" | "max_force" => &["motor"],
        "hertz" => &["spring", "linear_spring", "angular_spring"],
        _ => return None,
    };
    let root = DeTable::parse(text).ok()?;
    let table = table_at(root.get_ref(), path)?;
    owners.iter().find_map(|owner| {
        table.iter().find_map(|(k, v)| match v.get_ref() {
            DeValue::Table(inner)
                if k.get_ref().as_ref() == *owner
                    && !inner.iter().any(|(n, _)| n.get_ref().as_ref() == key) =>
            {
                Some(path.key(owner))
            }
            _ => None,
        })
    })
}

fn table_at<'a, 'i>(root: &'a DeTable<'i>, path: &FieldPath) -> Option<&'a DeTable<'i>> {
    let mut table = root;
    let mut value: Option<&DeValue<'i>> = None;
    for segment in &path.0 {
        value = Some(match (segment, value) {
            (Segment::Key(k), None | Some(DeValue::Table(_))) => table
                .iter()
                .find(|(key, _)| key.get_ref().as_ref() == k.as_str())
                .map(|(_, v)| v.get_ref())?,
            (Segment::Index(i), Some(DeValue::Array(a))) => a.get(*i).map(|v| v.get_ref())?,
            _ => return None,
        });
        if let Some(DeValue::Table(t)) = value {
            table = t;
        }
    }
    match value {
        Some(DeValue::Table(t)) => Some(t),
        _ => None,
    }
}

/// serde's message in the user's words: "expected …, found …" with TOML's
/// names for types (a number, an array, a table) instead of Rust's.
pub(crate) fn plain(message: &str, datetime: Option<&str>) -> String {
    if let Some(rest) = message.strip_prefix("invalid type: ") {
        if let Some((found, expected)) = rest.split_once(", expected ") {
            let found = match (found, datetime) {
                ("date-time", Some(d)) => format!("the date-time {d} (a scene has no dates)"),
                _ => found_words(found),
            };
            return format!("expected {}, found {found}", expected_words(expected));
        }
    }
    if let Some(rest) = message.strip_prefix("invalid value: ") {
        if let Some((found, expected)) = rest.split_once(", expected ") {
            return format!(
                "expected {}, found {}",
                expected_words(expected),
                found_words(found)
            );
        }
    }
    if let Some(rest) = message.strip_prefix("invalid length ") {
        if let Some((length, expected)) = rest.split_once(", expected ") {
            return format!(
                "expected {}, found {length} element{}",
                expected_words(expected),
                if length == "1" { "" } else { "s" }
            );
        }
    }
    if let Some(rest) = message.strip_prefix("unknown variant ") {
        return format!("unknown name {rest}");
    }
    message.to_owned()
}

/// serde's "found" part: `integer \`3\``, `string "x"`, `map`, ...
fn found_words(found: &str) -> String {
    if let Some(rest) = found.strip_prefix("integer `") {
        let digits = rest.trim_end_matches(" as i128").trim_end_matches('`');
        let digits = digits.trim_end_matches('`');
        if rest.ends_with("as i128") {
            return format!(
                "the integer {digits}, beyond TOML's 64-bit integers (write it with an exponent, e.g. 1e20, to make it a float)"
            );
        }
        return format!("the integer {digits}");
    }
    if let Some(rest) = found.strip_prefix("floating point `") {
        let text = rest.trim_end_matches('`');
        // serde prints the float in full (320 digits for 1e-320): short form.
        return match text.parse::<f64>() {
            Ok(v) => format!("the number {}", engine::error::readable(v)),
            Err(_) => format!("the number {text}"),
        };
    }
    if let Some(rest) = found.strip_prefix("string ") {
        return format!("the string {rest}");
    }
    if let Some(rest) = found.strip_prefix("boolean `") {
        return format!("the boolean {}", rest.trim_end_matches('`'));
    }
    match found {
        "map" => "a table".into(),
        "sequence" => "an array".into(),
        "date-time" => "a date-time (a scene has no dates)".into(),
        other => other.to_owned(),
    }
}

/// serde's "expected" part.
fn expected_words(expected: &str) -> String {
    match expected {
        "f64" | "f32" => return "a number".into(),
        "a sequence" => return "an array".into(),
        "variant identifier" => return "a name (a string)".into(),
        "a boolean" | "a string" => return expected.into(),
        _ => {}
    }
    if [
        "i8", "i16", "i32", "i64", "u8", "u16", "u32", "u64", "usize",
    ]
    .contains(&expected)
    {
        return "an integer".into();
    }
    if expected.starts_with("internally tagged enum ") {
        return "a table with a `type`".into();
    }
    if expected.starts_with("struct ") || expected.starts_with("a map") {
        return "a table".into();
    }
    if expected.starts_with("enum ") {
        return "one of the names the format lists".into();
    }
    expected
        .replace("a sequence", "an array")
        .replace("sequence", "array")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rust_names_become_toml_names() {
        assert_eq!(
            plain(
                "invalid type: integer `3`, expected internally tagged enum ShapeSpec",
                None
            ),
            "expected a table with a `type`, found the integer 3"
        );
        assert_eq!(
            plain("invalid type: map, expected f64", None),
            "expected a number, found a table"
        );
        assert_eq!(
            plain("invalid type: sequence, expected struct BodySpec", None),
            "expected a table, found an array"
        );
        let big = plain(
            "invalid type: integer `99999999999999999999` as i128, expected f64",
            None,
        );
        assert!(
            big.starts_with(
                "expected a number, found the integer 99999999999999999999, beyond TOML's 64-bit"
            ),
            "{big}"
        );
        assert_eq!(
            plain(
                "invalid type: integer `3`, expected variant identifier",
                None
            ),
            "expected a name (a string), found the integer 3"
        );
    }
}

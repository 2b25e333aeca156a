//! From field paths to lines and back, using toml's spanned document tree
//! ([`toml::de::DeTable`], whose keys and values are
//! [`toml::Spanned`]).
//!
//! - Validation knows the field (`bodies[1].mass`) and needs its line:
//!   [`position_of`] walks the tree along the path and returns where the
//!   value starts (or, if the key is absent, where its table starts).
//! - serde knows the byte offset of a bad value and nothing of its path:
//!   [`path_at`] finds the deepest key or value whose span holds the offset.
//!
//! The spans of a table opened by a header (`[simulation]`, `[[bodies]]`)
//! cover the header line, so a missing key points at its table's header.

use crate::error::{FieldPath, Segment};
use std::ops::Range;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// 1-based line and column (in characters) of a byte offset in `source`.
pub(crate) fn line_column(source: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(source.len());
    while !source.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &source[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = source[line_start..offset].chars().count() + 1;
    (line, column)
}

/// Line and column of the value at `path`, or of the nearest enclosing
/// value that exists. `None` if the text does not parse.
pub(crate) fn position_of(source: &str, path: &FieldPath) -> Option<(usize, usize)> {
    let root = DeTable::parse(source).ok()?;
    let mut span = root.span();
    let mut node = Node::Table(root.get_ref());
    for segment in &path.0 {
        let next = match (segment, node) {
            (Segment::Key(key), Node::Table(table)) => table
                .iter()
                .find(|(k, _)| k.get_ref().as_ref() == key.as_str())
                .map(|(_, v)| v),
            (Segment::Index(i), Node::Value(DeValue::Array(array))) => array.get(*i),
            (Segment::Key(key), Node::Value(DeValue::Table(table))) => table
                .iter()
                .find(|(k, _)| k.get_ref().as_ref() == key.as_str())
                .map(|(_, v)| v),
            _ => None,
        };
        match next {
            Some(value) => {
                span = value.span();
                node = Node::Value(value.get_ref());
            }
            None => break,
        }
    }
    Some(line_column(source, span.start))
}

/// Where `key` sits in the table at `table`: directly (`table.key`), or
/// in one of its inline tables (`table.child.key`, the first that has it);
/// `None` if neither. For errors that serde reports on a whole buffered
/// table, naming a key of a table inside it.
pub(crate) fn key_below(source: &str, table: &FieldPath, key: &str) -> Option<FieldPath> {
    let root = DeTable::parse(source).ok()?;
    let mut node = Node::Table(root.get_ref());
    for segment in &table.0 {
        let next = match (segment, node) {
            (Segment::Key(k), Node::Table(t)) => t
                .iter()
                .find(|(name, _)| name.get_ref().as_ref() == k.as_str())
                .map(|(_, v)| v),
            (Segment::Index(i), Node::Value(DeValue::Array(array))) => array.get(*i),
            (Segment::Key(k), Node::Value(DeValue::Table(t))) => t
                .iter()
                .find(|(name, _)| name.get_ref().as_ref() == k.as_str())
                .map(|(_, v)| v),
            _ => None,
        };
        node = Node::Value(next?.get_ref());
    }
    let entries: Vec<_> = match node {
        Node::Table(t) | Node::Value(DeValue::Table(t)) => t.iter().collect(),
        Node::Value(_) => return None,
    };
    if entries.iter().any(|(k, _)| k.get_ref().as_ref() == key) {
        return Some(table.key(key));
    }
    entries.iter().find_map(|(k, v)| match v.get_ref() {
        DeValue::Table(inner) if inner.iter().any(|(n, _)| n.get_ref().as_ref() == key) => {
            Some(table.key(k.get_ref()).key(key))
        }
        _ => None,
    })
}

#[derive(Clone, Copy)]
enum Node<'a, 'i> {
    Table(&'a DeTable<'i>),
    Value(&'a DeValue<'i>),
}

/// The path of the deepest key or value whose span contains `offset` (the
/// root path if none, or if the text does not parse).
pub(crate) fn path_at(source: &str, offset: Range<usize>) -> FieldPath {
    let Ok(root) = DeTable::parse(source) else {
        return FieldPath::root();
    };
    let mut best = FieldPath::root();
    search_table(root.get_ref(), &FieldPath::root(), &offset, &mut best);
    best
}

fn contains(span: &Range<usize>, target: &Range<usize>) -> bool {
    span.start <= target.start && target.end <= span.end.max(span.start + 1)
}

fn search_table(
    table: &DeTable<'_>,
    path: &FieldPath,
    target: &Range<usize>,
    best: &mut FieldPath,
) {
    for (key, value) in table.iter() {
        let here = path.key(key.get_ref());
        if contains(&key.span(), target) && here.0.len() > best.0.len() {
            *best = here.clone();
        }
        search_value(value, &here, target, best);
    }
}

fn search_value(
    value: &Spanned<DeValue<'_>>,
    path: &FieldPath,
    target: &Range<usize>,
    best: &mut FieldPath,
) {
    if contains(&value.span(), target) && path.0.len() > best.0.len() {
        *best = path.clone();
    }
    match value.get_ref() {
        DeValue::Table(table) => search_table(table, path, target, best),
        DeValue::Array(array) => {
            for (i, item) in array.iter().enumerate() {
                search_value(item, &path.index(i), target, best);
            }
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DOC: &str = "[simulation]\ndt = 0.1\n\n[[bodies]]\nname = \"a\"\n\n[[bodies]]\nname = \"b\"\nmass = -1\nshape = { type = \"polygon\", vertices = [[0, 0], [1, 0],\n  [0.2, 0.2]] }\n";

    fn path(parts: &[&str]) -> FieldPath {
        FieldPath(
            parts
                .iter()
                .map(|p| match p.parse::<usize>() {
                    Ok(i) => Segment::Index(i),
                    Err(_) => Segment::Key((*p).to_owned()),
                })
                .collect(),
        )
    }

    #[test]
    fn line_column_counts_from_one_in_characters() {
        assert_eq!(line_column("ab\ncé d", 0), (1, 1));
        assert_eq!(line_column("ab\ncé d", 3), (2, 1));
        assert_eq!(line_column("ab\ncé d", 7), (2, 4));
        assert_eq!(line_column("ab", 99), (1, 3));
    }

    #[test]
    fn a_field_path_finds_its_line() {
        assert_eq!(position_of(DOC, &path(&["simulation", "dt"])), Some((2, 6)));
        assert_eq!(
            position_of(DOC, &path(&["bodies", "1", "mass"])),
            Some((9, 8))
        );
        let vertex = path(&["bodies", "1", "shape", "vertices", "2"]);
        assert_eq!(position_of(DOC, &vertex), Some((11, 3)));
    }

    #[test]
    fn a_missing_key_points_at_its_table() {
        let p = path(&["bodies", "0", "mass"]);
        assert_eq!(position_of(DOC, &p), Some((4, 1)));
    }

    #[test]
    fn an_offset_finds_the_deepest_path() {
        let at = DOC.find("-1").unwrap();
        assert_eq!(path_at(DOC, at..at + 2).to_string(), "bodies[1].mass");
        let at = DOC.find("[0.2").unwrap();
        let p = path_at(DOC, at + 1..at + 4);
        assert_eq!(p.to_string(), "bodies[1].shape.vertices[2][0]");
    }
}

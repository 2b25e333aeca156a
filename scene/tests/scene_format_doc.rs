//! `docs/scene_format.md` kept in step with the code.
//!
//! 1. Every key the format accepts is documented. The keys are not listed
//!    by hand: they are read from the serde structures of
//!    `scene/src/format.rs` and `scene/src/generate.rs` themselves, which
//!    all deny unknown fields. Each table is fed a key `__probe__`, and
//!    serde's refusal ("unknown field `__probe__`, expected one of `a`,
//!    `b`, ...") lists every key the table accepts; an unknown `type`
//!    lists every type, an unknown value of an enumerated field every
//!    value. A key added to a structure without a line in the doc fails
//!    here, saying which key to document and under which heading.
//! 2. Every ```toml block of the doc is a whole scene file, loaded through
//!    the scene loader ([`Scene::parse_str`]); every section of a table
//!    has at least one.

use scene::Scene;
use scene::format::SceneFile;

const DOC_PATH: &str = "docs/scene_format.md";

fn doc() -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/scene_format.md");
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("reading {DOC_PATH}: {e}"))
}

/// The names serde lists after "expected" in its refusal of `probe` (a
/// scene text holding `__probe__` where a key, a type or a value goes).
fn accepted(probe: &str) -> Vec<String> {
    let error = match toml::from_str::<SceneFile>(probe) {
        Ok(_) => panic!("the probe was accepted, so it lists nothing:\n{probe}"),
        Err(e) => e.message().to_owned(),
    };
    assert!(
        error.contains("__probe__"),
        "the probe failed for another reason than its `__probe__` ({error}):\n{probe}"
    );
    let Some((_, expected)) = error.split_once("expected") else {
        panic!("serde's message lists no names: {error}\n{probe}");
    };
    expected
        .split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_owned)
        .collect()
}

/// A section of the doc: from a heading holding `title` to the next
/// heading of the same or a higher level.
fn section<'d>(doc: &'d str, title: &str) -> Option<&'d str> {
    let mut start = None;
    let mut level = 0;
    let mut offset = 0;
    for line in doc.split_inclusive('\n') {
        let hashes = line.chars().take_while(|&c| c == '#').count();
        if hashes > 0 && line[hashes..].starts_with(' ') {
            if let Some(s) = start {
                if hashes <= level {
                    return Some(&doc[s..offset]);
                }
            } else if line.contains(title) {
                start = Some(offset);
                level = hashes;
            }
        }
        offset += line.len();
    }
    start.map(|s| &doc[s..])
}

/// The `type` values of a tagged table (`[[forces]]`, `shape`, ...), from
/// a probe with `type = "__probe__"` at `place`.
fn types(place: &str) -> Vec<String> {
    accepted(place)
}

/// The heading of the section documenting `table` (and `type`, if tagged).
fn heading(table: &str, kind: Option<&str>) -> String {
    match kind {
        Some(kind) => format!("`{table} type = \"{kind}\"`"),
        None => format!("`{table}`"),
    }
}

/// A table of the format, probed: its heading in the doc, and its keys.
struct Table {
    heading: String,
    keys: Vec<String>,
}

/// Keys of a tagged table's variants, probed by `make(kind)` (a scene text
/// with the table of type `kind` holding `__probe__ = 1`).
fn tagged(table: &str, types_probe: &str, make: impl Fn(&str) -> String) -> Vec<Table> {
    types(types_probe)
        .into_iter()
        .map(|kind| Table {
            heading: heading(table, Some(&kind)),
            keys: accepted(&make(&kind)),
        })
        .collect()
}

/// Every table of the format with its keys, read from the code.
fn tables() -> Vec<Table> {
    let mut out = vec![
        Table {
            heading: "The file".into(),
            keys: accepted("__probe__ = 1\n"),
        },
        Table {
            heading: heading("[simulation]", None),
            keys: accepted("[simulation]\n__probe__ = 1\n"),
        },
        Table {
            heading: heading("[[bodies]]", None),
            keys: accepted("[[bodies]]\n__probe__ = 1\n"),
        },
        Table {
            heading: heading("[contact]", None),
            keys: accepted("[contact]\n__probe__ = 1\n"),
        },
        Table {
            heading: heading("[linear_test]", None),
            keys: accepted("[linear_test]\n__probe__ = 1\n"),
        },
    ];
    out.extend(tagged(
        "shape",
        "[[bodies]]\nshape = { type = \"__probe__\" }\n",
        |k| format!("[[bodies]]\nshape = {{ type = \"{k}\", __probe__ = 1 }}\n"),
    ));
    for table in ["forces", "events", "joints", "generate"] {
        out.extend(tagged(
            &format!("[[{table}]]"),
            &format!("[[{table}]]\ntype = \"__probe__\"\n"),
            |k| format!("[[{table}]]\ntype = \"{k}\"\n__probe__ = 1\n"),
        ));
    }
    // Sub-tables of joints, documented in their joint's table as
    // `sub.key` rows.
    let sub_tables = [
        ("revolute", "motor"),
        ("revolute", "spring"),
        ("prismatic", "motor"),
        ("prismatic", "spring"),
        ("distance", "spring"),
        ("weld", "linear_spring"),
        ("weld", "angular_spring"),
    ];
    for (kind, sub) in sub_tables {
        let keys = accepted(&format!(
            "[[joints]]\ntype = \"{kind}\"\n{sub} = {{ __probe__ = 1 }}\n"
        ));
        out.push(Table {
            heading: heading("[[joints]]", Some(kind)),
            keys: keys.iter().map(|k| format!("{sub}.{k}")).collect(),
        });
    }
    out
}

/// Enumerated values: (heading of the section, key, values read from the
/// code), each value to appear in that section as `"value"`.
fn enumerated_values() -> Vec<(String, &'static str, Vec<String>)> {
    vec![
        (
            heading("[[bodies]]", None),
            "kind",
            accepted("[[bodies]]\nkind = \"__probe__\"\n"),
        ),
        (
            heading("[contact]", None),
            "model",
            accepted("[contact]\nmodel = \"__probe__\"\n"),
        ),
        (
            heading("[contact]", None),
            "toi_method",
            accepted("[contact]\ntoi_method = \"__probe__\"\n"),
        ),
        (
            heading("[[generate]]", Some("grid")),
            "shapes",
            accepted("[[generate]]\ntype = \"grid\"\nshapes = [\"__probe__\"]\n"),
        ),
        (
            heading("[[generate]]", Some("grid")),
            "kind",
            accepted("[[generate]]\ntype = \"grid\"\nkind = \"__probe__\"\n"),
        ),
    ]
}

#[test]
fn every_key_the_format_accepts_is_documented() {
    let doc = doc();
    let mut missing = Vec::new();
    let tables = tables();
    assert!(
        tables.len() > 20 && tables.iter().all(|t| !t.keys.is_empty()),
        "the probes found too few tables or keys: is serde's message still \
         \"unknown field ..., expected ...\"?"
    );
    for table in &tables {
        let Some(text) = section(&doc, &table.heading) else {
            let message = format!(
                "- no section for {h}: add a heading \"### {h}\" to {DOC_PATH}, with a table \
                 of its keys (| key | unit | default | meaning |) and a minimal ```toml example \
                 (a whole scene file: this test loads it)",
                h = table.heading
            );
            if !missing.contains(&message) {
                missing.push(message);
            }
            continue;
        };
        for key in &table.keys {
            if !text.contains(&format!("| `{key}` |")) {
                missing.push(format!(
                    "- key `{key}` of {h} is accepted by the code (scene/src/format.rs or \
                     generate.rs) but not documented: add a row \
                     \"| `{key}` | unit | default | meaning |\" to the table under the heading \
                     {h} in {DOC_PATH}",
                    h = table.heading
                ));
            }
        }
    }
    for (h, key, values) in enumerated_values() {
        let text = section(&doc, &h).unwrap_or("");
        for value in values {
            if !text.contains(&format!("\"{value}\"")) {
                missing.push(format!(
                    "- value \"{value}\" of `{key}` is accepted by the code but not named in \
                     the section {h} of {DOC_PATH}: say what `{key} = \"{value}\"` does there"
                ));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "{DOC_PATH} is behind the code:\n{}",
        missing.join("\n")
    );
}

/// The ```toml blocks of `doc`, each with the line it starts on.
fn toml_blocks(doc: &str) -> Vec<(usize, String)> {
    let mut blocks = Vec::new();
    let mut current: Option<(usize, String)> = None;
    for (i, line) in doc.lines().enumerate() {
        match &mut current {
            None if line.trim_start() == "```toml" => current = Some((i + 2, String::new())),
            Some(_) if line.trim_start() == "```" => blocks.extend(current.take()),
            Some((_, text)) => {
                text.push_str(line);
                text.push('\n');
            }
            None => {}
        }
    }
    blocks
}

#[test]
fn every_example_of_the_doc_loads() {
    let doc = doc();
    let blocks = toml_blocks(&doc);
    assert!(blocks.len() > 20, "{DOC_PATH}: too few examples found");
    let mut failures = Vec::new();
    for (line, text) in &blocks {
        let origin = format!("{DOC_PATH}, example at line {line}");
        if let Err(e) = Scene::parse_str(&origin, text) {
            failures.push(format!("- {e}"));
        }
    }
    assert!(
        failures.is_empty(),
        "examples of {DOC_PATH} the scene loader refuses (each must be a whole scene file):\n{}",
        failures.join("\n")
    );
}

#[test]
fn every_table_has_an_example() {
    let doc = doc();
    let mut missing = Vec::new();
    for table in tables() {
        if let Some(text) = section(&doc, &table.heading)
            && !text.contains("```toml")
        {
            missing.push(format!(
                "- the section {} has no ```toml example: add a minimal whole scene using it",
                table.heading
            ));
        }
    }
    assert!(missing.is_empty(), "{DOC_PATH}:\n{}", missing.join("\n"));
}

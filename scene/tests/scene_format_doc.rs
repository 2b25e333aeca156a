//! `docs/scene_format.md` kept in step with the code.
//!
//! 1. Every key the format accepts is documented. The keys are not listed
//!    by hand: they are read from the serde structures of
//!    `scene/src/format.rs` and `scene/src/generate.rs` themselves, which
//!    all deny unknown fields. Each table is fed a key `__probe__`, and
//!    serde's refusal ("unknown field `__probe__`, expected one of `a`,
//!    `b`, ...") lists every key the table accepts; an unknown `type`
//!    lists every type, an unknown value of an enumerated field every
//!    value; each key is also fed a table `{ __probe__ = 1 }`, which finds
//!    the inline tables (a joint's `motor`, its `spring`) and their keys,
//!    documented as `motor.speed` rows. A key, a type or an inline table
//!    added to the structures without a line in the doc fails here, saying
//!    which key to document and under which heading.
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
/// scene text holding `__probe__` where a key, a type or a value goes);
/// `None` when the text is refused for another reason (the place does
/// not take a table of keys) or accepted.
fn listed(probe: &str) -> Option<Vec<String>> {
    let error = toml::from_str::<SceneFile>(probe)
        .err()?
        .message()
        .to_owned();
    if !error.contains("__probe__") {
        return None;
    }
    let (_, expected) = error.split_once("expected")?;
    Some(
        expected
            .split('`')
            .skip(1)
            .step_by(2)
            .map(str::to_owned)
            .collect(),
    )
}

/// [`listed`], which must list something here.
fn accepted(probe: &str) -> Vec<String> {
    listed(probe).unwrap_or_else(|| {
        let error = toml::from_str::<SceneFile>(probe)
            .err()
            .map(|e| e.to_string());
        panic!(
            "the probe lists no names: is serde's message still \"unknown field `__probe__`, \
             expected ...\"? ({error:?})\n{probe}"
        )
    })
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

/// Every table of the format with its keys, read from the code: the
/// tables, each type of the tagged ones (`shape`, `[[forces]]`,
/// `[[events]]`, `[[joints]]`, `[[generate]]`), and the inline tables
/// found among their keys (a joint's `motor` or `spring`), whose keys are
/// documented in their table as `motor.speed` rows. Types and inline
/// tables added later are found the same way.
fn tables() -> Vec<Table> {
    // Each table's heading and a scene text with `@@` where a key goes.
    let mut templates: Vec<(String, String)> =
        ["[simulation]", "[[bodies]]", "[contact]", "[linear_test]"]
            .iter()
            .map(|t| (heading(t, None), format!("{t}\n@@\n")))
            .collect();
    for kind in accepted("[[bodies]]\nshape = { type = \"__probe__\" }\n") {
        templates.push((
            heading("shape", Some(&kind)),
            format!("[[bodies]]\nshape = {{ type = \"{kind}\", @@ }}\n"),
        ));
    }
    for table in ["forces", "events", "joints", "generate"] {
        for kind in accepted(&format!("[[{table}]]\ntype = \"__probe__\"\n")) {
            templates.push((
                heading(&format!("[[{table}]]"), Some(&kind)),
                format!("[[{table}]]\ntype = \"{kind}\"\n@@\n"),
            ));
        }
    }
    let mut out = vec![Table {
        heading: "The file".into(),
        keys: accepted("__probe__ = 1\n"),
    }];
    for (heading, template) in templates {
        let keys = accepted(&template.replace("@@", "__probe__ = 1"));
        for key in &keys {
            let inline = template.replace("@@", &format!("{key} = {{ __probe__ = 1 }}"));
            // A table of keys refuses `__probe__` as an unknown field; a
            // name (`kind`, `model`) given as a table, as an unknown variant.
            let is_table_of_keys = toml::from_str::<SceneFile>(&inline)
                .err()
                .is_some_and(|e| e.message().starts_with("unknown field"));
            if let Some(inner) = listed(&inline).filter(|_| is_table_of_keys) {
                out.push(Table {
                    heading: heading.clone(),
                    keys: inner.iter().map(|k| format!("{key}.{k}")).collect(),
                });
            }
        }
        out.push(Table { heading, keys });
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

#[test]
fn the_probes_find_the_joints_inline_tables() {
    // The inline tables known today: a change in how they are found must
    // not lose them silently.
    let tables = tables();
    for key in [
        "motor.max_torque",
        "motor.max_force",
        "spring.hertz",
        "spring.target",
        "linear_spring.hertz",
        "angular_spring.damping_ratio",
    ] {
        assert!(
            tables.iter().any(|t| t.keys.iter().any(|k| k == key)),
            "no table has {key}"
        );
    }
}

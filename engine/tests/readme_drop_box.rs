//! The README's library example is `engine/examples/drop_box.rs`, which CI
//! runs: the two must not drift apart.

#[test]
fn the_readme_shows_the_drop_box_example_as_it_is() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("../README.md")).expect("README.md");
    let example =
        std::fs::read_to_string(root.join("examples/drop_box.rs")).expect("examples/drop_box.rs");
    // The example without its module doc and the blank line after it.
    let code: String = example
        .lines()
        .skip_while(|l| l.starts_with("//!") || l.trim().is_empty())
        .map(|l| format!("{l}\n"))
        .collect();
    let marker = "A box dropped on the ground:";
    let after = readme
        .split_once(marker)
        .map(|(_, rest)| rest)
        .expect("README.md: the library example's sentence");
    let block = after
        .split_once("```rust\n")
        .and_then(|(_, rest)| rest.split_once("```"))
        .map(|(block, _)| block)
        .expect("README.md: a ```rust block after the sentence");
    assert_eq!(
        block, code,
        "README.md's drop_box snippet differs from engine/examples/drop_box.rs: copy the example \
         (without its //! lines) into the README"
    );
}

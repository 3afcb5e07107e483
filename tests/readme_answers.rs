//! The README's Pareto answers (which technique is the most accurate within each time budget,
//! per effect family) are what `ssgi::sweep::answers` reads from the committed sweep.json files
//! they name, not typed by hand. Regenerate with `cargo run --example readme_answers`.

#[test]
fn the_readmes_answers_are_those_of_the_committed_sweeps() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("README.md")).unwrap();
    let (regenerated, blocks) = ssgi::sweep::answers::rewrite_blocks(&text, root).unwrap();
    assert!(
        blocks >= 2,
        "the README answers for AO and indirect light: {blocks} block(s)"
    );
    assert!(
        regenerated == text,
        "README.md's answers blocks differ from their sweeps: run `cargo run --example \
         readme_answers`"
    );
}

//! Rewrite the README's answers blocks (`<!-- answers: PATH BUFFER -->`) from the sweep.json
//! files they name: `cargo run --example readme_answers`. tests/readme_answers.rs fails when
//! they differ.

fn main() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = root.join("README.md");
    let text = std::fs::read_to_string(&readme).expect("README.md");
    match ssgi::sweep::answers::rewrite_blocks(&text, root) {
        Ok((new, blocks)) => {
            std::fs::write(&readme, new).expect("write README.md");
            println!("rewrote {blocks} answers block(s) in README.md");
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}

//! Re-render the golden images of tests/golden.rs (the test only compares; it never writes).
//!
//! `cargo run --example bless_goldens` renders every case on the default Vulkan device (bless on
//! lavapipe, as the tests run); `-- NAME...` only the cases whose names contain one of the
//! NAMEs. Each case prints how its new image compares with the old, for the commit message that
//! says why the pixels moved.

#[path = "../tests/common/mod.rs"]
mod common;

use common::golden::{self, Case};

fn main() {
    let filters: Vec<String> = std::env::args().skip(1).collect();
    let chosen: Vec<Case> = golden::cases()
        .into_iter()
        .filter(|c| filters.is_empty() || filters.iter().any(|f| c.name.contains(f.as_str())))
        .collect();
    if chosen.is_empty() {
        eprintln!("no golden case matches {filters:?}");
        std::process::exit(2);
    }
    std::fs::create_dir_all(golden::golden_dir()).expect("create tests/golden");
    for case in &chosen {
        let got = golden::render(case);
        println!("{}: {}", case.name, change(case, &got));
        image::save_buffer(
            case.path(),
            &got,
            golden::SIZE,
            golden::SIZE,
            image::ExtendedColorType::Rgba8,
        )
        .unwrap_or_else(|e| panic!("write {}: {e}", case.path().display()));
    }
    println!("blessed {} golden image(s)", chosen.len());
}

/// How `got` differs from the case's current golden image.
fn change(case: &Case, got: &[u8]) -> String {
    let Ok(old) = image::open(case.path()) else {
        return "new".into();
    };
    let old = old.to_rgba8();
    if old.as_raw().as_slice() == got {
        return "unchanged".into();
    }
    match common::golden_compare(got, old.as_raw(), golden::SIZE) {
        None => "changed within the tolerance".into(),
        Some(msg) => format!("changed: {msg}"),
    }
}

//! Golden-image regression: 64x64 renders against PNGs in `tests/golden/`, one per case of
//! `common::golden::cases()`:
//! - every combination of direct light, AO and indirect light, with reuse on and off, on the
//!   Cornell box and the bunny in a box, along four frames of a slow orbit (so reprojection,
//!   disocclusion and accumulation all take part);
//! - on the Cornell box, a still view converged (the rotation limit's patterns and four frames
//!   more): AO alone, indirect light alone, the three with direct light; SSDO's SSAO form
//!   alone and one-step SSDO with direct light; indirect light alone filtered by CCIPCA and by
//!   the 11x11 and 17x17 joint bilateral filters, and gathered interleaved in 2x2 blocks; SRAA
//!   and shadow-aware SRAA on every effect;
//! - two-step SSDO with direct light, without reuse, along the orbit; and a converged view of
//!   every effect that then moves three orbit steps, its histories resampled bilinearly and
//!   from the nearest point.
//!
//! The goldens pin the renderer's behaviour across refactors; a change that is meant to move
//! pixels re-renders them in its own commit and says why (the last: the G-buffer's albedo in
//! fp16 instead of 8-bit UNORM, 1-2 codes on about a quarter of the pixels; the converged,
//! SSDO, filter, antialiasing and resampling cases were added later without re-rendering the
//! combinations).
//!
//! Tolerance: lavapipe is deterministic for a given shader binary, so the same code reproduces
//! every byte. A refactor may legitimately reorder floating-point operations (another shader
//! permutation mechanism, another evaluation order), which moves a channel by a code or two
//! after tonemapping. So each channel may differ by at most `common::MAX_CHANNEL_DIFF` codes,
//! and at most `common::MAX_CHANGED_FRACTION` of the pixels may differ at all; anything larger
//! is a change in behaviour, and the failure message names the image, the worst pixel and both
//! values.
//!
//! Re-bless (only for an intended change of the image, stated in the commit), on lavapipe:
//! `cargo run --example bless_goldens` (all cases) or `cargo run --example bless_goldens --
//! NAME...` (the cases whose names contain one of the NAMEs). The test never writes an image:
//! it fails when `SSGI_BLESS_GOLDEN` is set, naming that command.

mod common;

use common::golden::{self, Group, BLESS_COMMAND, BLESS_VARIABLE};

/// Render every case of `group` and compare it with its golden image.
fn check(group: Group) {
    assert!(
        std::env::var_os(BLESS_VARIABLE).is_none(),
        "{BLESS_VARIABLE} is set, but the test never writes its own expectation: unset it and \
         bless with `{BLESS_COMMAND}` (on lavapipe; see tests/golden.rs)"
    );
    let mut failures = Vec::new();
    for case in golden::cases().iter().filter(|c| c.group == group) {
        let file = case.path();
        let want = match image::open(&file) {
            Ok(img) => img.to_rgba8(),
            Err(e) => {
                failures.push(format!(
                    "{}: golden image missing ({e}); render it with `{BLESS_COMMAND} -- {}`",
                    file.display(),
                    case.name
                ));
                continue;
            }
        };
        assert_eq!(
            want.dimensions(),
            (golden::SIZE, golden::SIZE),
            "{}",
            file.display()
        );
        let got = golden::render(case);
        if let Some(msg) = common::golden_compare(&got, want.as_raw(), golden::SIZE) {
            failures.push(format!("{}: {msg}", file.display()));
        }
    }
    assert!(
        failures.is_empty(),
        "golden mismatch:\n{}",
        failures.join("\n")
    );
}

#[test]
fn golden_cornell_box() {
    check(Group::Cornell);
}

#[test]
fn golden_bunny_in_box() {
    check(Group::Bunny);
}

#[test]
fn golden_converged_effects() {
    check(Group::Converged);
}

#[test]
fn golden_filters_and_resampling() {
    check(Group::Filters);
}

/// Every image in `tests/golden/` is some case's and no two cases share a name: an image left
/// behind by a renamed case would otherwise go unchecked.
#[test]
fn every_golden_image_has_a_case() {
    let cases = golden::cases();
    let mut names: Vec<&str> = cases.iter().map(|c| c.name.as_str()).collect();
    names.sort_unstable();
    let before = names.len();
    names.dedup();
    assert_eq!(names.len(), before, "two cases share a name");
    for entry in std::fs::read_dir(golden::golden_dir()).expect("tests/golden") {
        let path = entry.expect("directory entry").path();
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
        assert!(
            path.extension().is_some_and(|e| e == "png") && names.binary_search(&stem).is_ok(),
            "{} is no golden case's image",
            path.display()
        );
    }
}

/// A frame of 64x64 RGBA8 pixels, all 10.
fn flat() -> Vec<u8> {
    vec![10u8; 4 * 64 * 64]
}

/// Add `by` to the green channel of the first `count` pixels.
fn shift_pixels(image: &mut [u8], count: usize, by: u8) {
    for px in image.chunks_mut(4).take(count) {
        px[1] += by;
    }
}

#[test]
fn comparison_catches_a_changed_pixel() {
    let a = flat();
    let mut b = a.clone();
    assert!(common::golden_compare(&a, &b, 64).is_none());
    b[4 * 100 + 1] = 10 + common::MAX_CHANNEL_DIFF + 1;
    let msg = common::golden_compare(&b, &a, 64).expect("a 4-code difference fails");
    assert!(msg.contains("(36, 1)"), "{msg}");
}

/// The per-channel limit and the changed-pixel limit each fail on their own, and images within
/// both pass.
#[test]
fn comparison_holds_both_limits() {
    let want = flat();
    let pixels = 64 * 64;
    // The most pixels that may differ: 81 of 4096 (1.98%).
    let allowed = (common::MAX_CHANGED_FRACTION * pixels as f64).floor() as usize;
    let mut within = want.clone();
    shift_pixels(&mut within, allowed, common::MAX_CHANNEL_DIFF);
    assert_eq!(common::golden_compare(&within, &want, 64), None);

    let mut one_too_deep = want.clone();
    shift_pixels(&mut one_too_deep, 1, common::MAX_CHANNEL_DIFF + 1);
    let msg = common::golden_compare(&one_too_deep, &want, 64).expect("a channel past the limit");
    assert!(msg.contains("1 pixels differ"), "{msg}");

    let mut one_too_many = want.clone();
    shift_pixels(&mut one_too_many, allowed + 1, 1);
    let msg = common::golden_compare(&one_too_many, &want, 64).expect("too many pixels");
    assert!(
        msg.contains(&format!("{} pixels differ", allowed + 1)) && msg.contains("worst 1 codes"),
        "{msg}"
    );
}

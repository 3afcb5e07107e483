//! The numerical audit and `ssgi stress`: the GPU reduction counts what a CPU count of the same
//! values finds (NaN, Inf, forbidden negatives, channel maxima), on a crafted image and on every
//! target of a real frame; the quick stress subset passes end to end and reports every case.

mod common;
#[path = "common/schema.rs"]
mod schema;

use ash::vk;
use ssgi::renderer::audit::{audit_images, audit_pipeline, AuditKind, AuditRequest};
use ssgi::resources::targets::Target;
use ssgi::vk::{upload_image, Access, Image, ImageDesc, Tracker};

/// CPU count of (nan, inf, negative, max |value| per channel) over RGBA texels.
fn cpu_stats(texels: &[[f32; 4]], channels: usize, signed_mask: u32) -> (u32, u32, u32, [f32; 4]) {
    let (mut nan, mut inf, mut neg, mut max) = (0, 0, 0, [0.0f32; 4]);
    for t in texels {
        for (c, &x) in t.iter().enumerate().take(channels) {
            if x.is_nan() {
                nan += 1;
            } else if x.is_infinite() {
                inf += 1;
            } else {
                if x < 0.0 && signed_mask & (1 << c) == 0 {
                    neg += 1;
                }
                max[c] = max[c].max(x.abs());
            }
        }
    }
    (nan, inf, neg, max)
}

#[test]
fn audit_counts_nan_inf_and_negatives_like_the_cpu() {
    let ctx = common::context();
    // 13x7 (not a multiple of the 8x8 workgroup): a mix of bad and good values.
    let (w, h) = (13u32, 7u32);
    let texels: Vec<[f32; 4]> = (0..w * h)
        .map(|i| {
            let f = i as f32;
            match i % 9 {
                0 => [f32::NAN, f, 0.5, 1.0],
                1 => [f, f32::INFINITY, -0.25, 2.0],
                2 => [-f, f32::NEG_INFINITY, f32::NAN, 3.0],
                3 => [1e30, -1e-30, f, f32::NAN],
                _ => [f * 0.5, -f, f, 0.0],
            }
        })
        .collect();
    let bytes: Vec<u8> = texels
        .iter()
        .flat_map(|t| t.iter().flat_map(|v| v.to_le_bytes()))
        .collect();
    let image = Image::new(
        &ctx,
        "audit.crafted",
        ImageDesc {
            width: w,
            height: h,
            format: vk::Format::R32G32B32A32_SFLOAT,
            usage: vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
        },
    )
    .unwrap();
    let mut tracker = Tracker::new();
    upload_image(
        &ctx,
        &mut tracker,
        &image,
        &bytes,
        Access::ComputeSampledRead,
    )
    .unwrap();
    let pipeline = audit_pipeline(&ctx).unwrap();
    for (channels, signed_mask) in [(4u32, 0u32), (4, 0b0110), (1, 0), (3, 0b0001)] {
        let request = AuditRequest {
            name: "crafted".into(),
            kind: AuditKind::Target,
            image: &image,
            channels,
            signed_mask,
        };
        let a = &audit_images(&ctx, &mut tracker, &pipeline, &[request]).unwrap()[0];
        let (nan, inf, neg, max) = cpu_stats(&texels, channels as usize, signed_mask);
        let what = format!("channels {channels}, signed {signed_mask:#b}: {a:?}");
        assert!(nan > 0 || channels < 4, "{what}");
        assert_eq!((a.nan, a.inf, a.negative), (nan, inf, neg), "{what}");
        assert_eq!(a.max_abs, max, "{what}");
        assert_eq!(a.texels, w * h, "{what}");
    }
    common::assert_clean(&ctx);
}

#[test]
fn audit_of_a_frame_matches_the_read_back_targets() {
    let ctx = common::context();
    let mut r = common::render(
        &ctx,
        ssgi::scene::cornell_box(),
        24,
        ssgi::config::pcf::Pcf::DEFAULT,
        3,
    );
    let audits = r.audit().unwrap();
    for (name, kind) in [
        ("ao.history", AuditKind::History),
        ("ao.moments", AuditKind::Moments),
        ("ao.registration", AuditKind::Registration),
        ("gbuffer_position", AuditKind::Target),
        ("gbuffer_normal", AuditKind::Target),
        ("rsm_flux", AuditKind::Target),
        ("direct", AuditKind::Target),
        ("indirect.history", AuditKind::History),
        ("shadow", AuditKind::Target),
        ("rsm_depth", AuditKind::Target),
    ] {
        let a = audits.iter().find(|a| a.name == name);
        let a = a.unwrap_or_else(|| panic!("no audit of {name}: {audits:#?}"));
        assert_eq!(a.kind, kind, "{name}");
    }
    for a in &audits {
        assert_eq!(a.bad_values(), 0, "{a:?}");
    }
    // The reduction's maxima equal the CPU's over the read-back images.
    for (target, name) in [
        (Target::GPosition, "gbuffer_position"),
        (Target::Direct, "direct"),
        (Target::RsmFlux, "rsm_flux"),
    ] {
        let image = r.read(target).unwrap();
        let texels: Vec<[f32; 4]> = (0..image.height)
            .flat_map(|y| (0..image.width).map(move |x| (x, y)))
            .map(|(x, y)| image.texel(x, y))
            .collect();
        let a = audits.iter().find(|a| a.name == name).unwrap();
        let signed = if target == Target::GPosition {
            0b0111
        } else {
            0
        };
        let (nan, inf, neg, max) = cpu_stats(&texels, 4, signed);
        assert_eq!((a.nan, a.inf, a.negative), (nan, inf, neg), "{name}");
        assert_eq!(a.max_abs, max, "{name}");
        assert!(max.iter().any(|m| *m > 0.0), "{name} is empty");
    }
    drop(r);
    common::assert_clean(&ctx);
}

/// `ssgi stress --quick`: every kind of case, each variant somewhere, the long run at 2,000
/// frames; passes, and its report has every case with values checked.
#[test]
fn quick_stress_matrix_passes() {
    let out = std::env::temp_dir().join(format!("ssgi-stress-{}", std::process::id()));
    std::fs::remove_dir_all(&out).ok();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_ssgi"))
        .args(["stress", "--quick", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "stress failed:\n{stdout}\n{stderr}"
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("stress.json")).unwrap()).unwrap();
    schema::assert_follows("stress", &report);
    let results = report["results"].as_array().unwrap();
    let names: std::collections::BTreeSet<&str> = results
        .iter()
        .map(|r| r["case"].as_str().unwrap())
        .collect();
    for case in [
        "scale-1e-3",
        "scale-1e5",
        "near-far-1e5",
        "camera-inside-geometry",
        "grazing-view",
        "slivers-and-huge-triangles",
        "light-inside-geometry",
        "size-1x1",
        "size-2x3",
        "rotation-limit-2048",
        "long-jitter",
    ] {
        assert!(names.contains(case), "{case} missing from {names:?}");
    }
    for r in results {
        assert!(r["values_checked"].as_u64().unwrap() > 0, "{r}");
        assert!(r["drift_rmse"].as_f64().is_some(), "{r}");
        assert_eq!(r["failures"].as_array().unwrap().len(), 0, "{r}");
    }
    // Every effect set meets both reuse modes somewhere.
    for effects in ["ao", "ssdo"] {
        for reuse in [true, false] {
            assert!(
                results
                    .iter()
                    .any(|r| r["effects"] == effects && r["reuse"] == reuse),
                "{effects} reuse {reuse}"
            );
        }
    }
    let long = results.iter().find(|r| r["case"] == "long-jitter").unwrap();
    assert!(long["frames"].as_u64().unwrap() >= 2000, "{long}");
    assert!(long["resizes"].as_u64().unwrap() >= 10, "{long}");
    // Host memory stays flat (lavapipe once leaked a recompiled shader per pass and frame).
    let growth = long["memory_growth_per_frame"].as_f64().unwrap();
    assert!(growth <= 4096.0, "{long}");
    assert_eq!(report["totals"]["failures"], 0);
    std::fs::remove_dir_all(&out).ok();
}

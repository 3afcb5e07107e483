//! The thesis's own numbers (Lin 2013), printed beside ours so a reader compares speed-ups
//! (ratios measured on one machine), not absolute frame rates across GPUs fifteen years apart.

use serde::Serialize;

/// Where and how the thesis measured (its section 4 text).
pub const SETUP: &str = "NVIDIA GeForce GTX 480, Intel Core i7 930, 512x512, SSAO 32 samples, \
                         one-bounce indirect light with 512 VPLs at half resolution";

/// One row of Table 4.1: frames per second.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Fps {
    pub ssao: f64,
    pub indirect: f64,
    /// SSAO + indirect + direct light.
    pub total: f64,
}

/// One scene of Table 4.1.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Scene41 {
    pub name: &'static str,
    pub faces: u32,
    /// "Reuse data: yes, blur: no".
    pub reuse: Fps,
    /// "Reuse data: no, blur: yes (Gaussian 5x5)".
    pub no_reuse: Fps,
}

impl Scene41 {
    /// How many times faster reuse is than no reuse, per column (fps ratio).
    pub fn speedups(&self) -> Fps {
        Fps {
            ssao: self.reuse.ssao / self.no_reuse.ssao,
            indirect: self.reuse.indirect / self.no_reuse.indirect,
            total: self.reuse.total / self.no_reuse.total,
        }
    }
}

const fn fps(ssao: f64, indirect: f64, total: f64) -> Fps {
    Fps {
        ssao,
        indirect,
        total,
    }
}

/// Table 4.1 of the thesis, as printed (all with 512 VPLs).
pub const TABLE_4_1: [Scene41; 4] = [
    Scene41 {
        name: "Venus",
        faces: 43_357,
        reuse: fps(206.0, 51.0, 46.0),
        no_reuse: fps(170.0, 34.0, 31.0),
    },
    Scene41 {
        name: "Dragon",
        faces: 6_514,
        reuse: fps(426.0, 73.0, 63.0),
        no_reuse: fps(280.0, 43.0, 38.0),
    },
    Scene41 {
        name: "Bunny",
        faces: 69_451,
        reuse: fps(147.0, 46.0, 41.0),
        no_reuse: fps(130.0, 32.0, 28.0),
    },
    Scene41 {
        name: "Buddha",
        faces: 100_000,
        reuse: fps(102.0, 34.0, 31.0),
        no_reuse: fps(89.0, 26.0, 23.0),
    },
];

/// The thesis's Table 4.1 entry for `name` (case-insensitive).
pub fn table_4_1(name: &str) -> Option<&'static Scene41> {
    TABLE_4_1.iter().find(|s| s.name.eq_ignore_ascii_case(name))
}

/// Tables 4.2-4.4 (Sponza, Sibenik, Conference walkthroughs) and Figure 4.10 are images in
/// the thesis; their numbers are not in its text, so there is nothing to print beside ours.
pub const WALKTHROUGH_NUMBERS_MISSING: &str =
    "The thesis's Tables 4.2-4.4 (Sponza, Sibenik and Conference walkthroughs) and Figure 4.10 \
     are figures; their frame rates and recomputed-pixel counts are not in the thesis text, so \
     no thesis numbers stand beside these. The thesis says only that the cached version is \
     \"mostly better\" and that more pixels are recomputed in the more complex scene.";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speedups_are_reuse_over_no_reuse() {
        let venus = table_4_1("venus").unwrap();
        let s = venus.speedups();
        assert!((s.ssao - 206.0 / 170.0).abs() < 1e-12);
        assert!((s.total - 46.0 / 31.0).abs() < 1e-12);
        // Reuse is faster in every column of every scene of the printed table.
        for scene in &TABLE_4_1 {
            let s = scene.speedups();
            assert!(
                s.ssao > 1.0 && s.indirect > 1.0 && s.total > 1.0,
                "{scene:?}"
            );
        }
        assert!(table_4_1("pyramids").is_none());
    }
}

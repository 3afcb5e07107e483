//! PCF soft-shadow kernels: the thesis's 49-sample grid baseline, hard shadows, and the rotated
//! Vogel disc accumulated with the cache.

/// The PCF kernel: a regular grid (the thesis's 49-sample baseline, or hard shadows), or a disc
/// of Vogel-spiral samples that is rotated and moved radially every frame and accumulated, so
/// over frames the taps fill the disc uniformly (the thesis's 9-sample PCF with the cache; many
/// samples in the fixed pattern 0 without reuse for references). Each pixel turns the disc by
/// its own interleaved-gradient-noise angle (shaders/include/patterns.glsl).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(tag = "kernel", rename_all = "lowercase")]
pub enum PcfKernel {
    Grid { side: u32 },
    Disc { samples: u32 },
}

/// PCF configuration: the kernel spread over +-`radius_texels` shadow-map texels.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Pcf {
    pub kernel: PcfKernel,
    pub radius_texels: f32,
}

impl Pcf {
    /// The thesis's baseline soft shadow: 49 samples on a 7x7 grid.
    pub const DEFAULT: Pcf = Pcf {
        kernel: PcfKernel::Grid { side: 7 },
        radius_texels: 3.0,
    };
    pub const HARD: Pcf = Pcf {
        kernel: PcfKernel::Grid { side: 1 },
        radius_texels: 0.0,
    };
    /// The thesis's 9-sample PCF, a new rotation and radial offset per frame, accumulated.
    pub const NINE: Pcf = Pcf {
        kernel: PcfKernel::Disc { samples: 9 },
        radius_texels: 3.0,
    };

    /// `hard`, `9` (the accumulated disc), another square count for a grid (25, 49, ...), or
    /// `disc:N` for an N-sample disc.
    pub fn parse(s: &str) -> Result<Pcf, String> {
        if s == "hard" || s == "1" {
            return Ok(Pcf::HARD);
        }
        if let Some(n) = s.strip_prefix("disc:") {
            let samples: u32 = n
                .parse()
                .map_err(|_| format!("--pcf disc:N takes a sample count, not {s:?}"))?;
            if !(1..=4096).contains(&samples) {
                return Err(format!("--pcf {s}: disc samples must be in 1..=4096"));
            }
            return Ok(Pcf {
                kernel: PcfKernel::Disc { samples },
                ..Pcf::NINE
            });
        }
        let n: u32 = s.parse().map_err(|_| {
            format!("--pcf takes 'hard', 9, a square sample count like 49, or disc:N, not {s:?}")
        })?;
        if n == 9 {
            return Ok(Pcf::NINE);
        }
        let side = (n as f64).sqrt().round() as u32;
        if side * side != n || !(2..=32).contains(&side) {
            return Err(format!(
                "--pcf {n}: the sample count must be 9 or a square between 4 and 1024 (25, 49, ...)"
            ));
        }
        Ok(Pcf {
            kernel: PcfKernel::Grid { side },
            radius_texels: Pcf::DEFAULT.radius_texels,
        })
    }

    pub fn samples(&self) -> u32 {
        match self.kernel {
            PcfKernel::Grid { side } => side * side,
            PcfKernel::Disc { samples } => samples,
        }
    }

    /// (kernel code for the shader: 0 grid, 1 disc; grid side or disc samples).
    pub fn shader_params(&self) -> (u32, u32) {
        match self.kernel {
            PcfKernel::Grid { side } => (0, side),
            PcfKernel::Disc { samples } => (1, samples),
        }
    }
}

//! The option values' parsers (strings to validated values), shared by the command line
//! (`cli::args`) and the sweep's keys (`sweep::keys`), and `--accumulate`'s choices.

use super::Epsilon;

/// `--accumulate` choices.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum AccumulateMode {
    Gated,
    Confidence,
    Ema,
    Mean,
}

/// A share of a frame's work: `5%` or `0.05`, in (0, 100] (above 1: more than a frame, e.g.
/// the thesis's 64x64 refresh tiles).
pub fn parse_fraction(s: &str) -> Result<f32, String> {
    let (number, scale) = match s.strip_suffix('%') {
        Some(p) => (p, 0.01),
        None => (s, 1.0),
    };
    let max = crate::config::MAX_REFRESH_BUDGET;
    match number.trim().parse::<f32>() {
        Ok(v) if v.is_finite() && v * scale > 0.0 && v * scale <= max => Ok(v * scale),
        _ => Err(format!(
            "{s:?} is not a share in (0, {max}]: write a percentage like 5% or a fraction like 0.05"
        )),
    }
}

pub fn parse_bias(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(b) if b.is_finite() && b >= 0.0 => Ok(b),
        _ => Err(format!("--bias takes a finite number >= 0, not {s:?}")),
    }
}

pub fn parse_gate(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(g) if g.is_finite() && g > 0.0 => Ok(g),
        _ => Err(format!(
            "--gate takes a number of standard deviations > 0, not {s:?}"
        )),
    }
}

pub fn parse_ema_alpha(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(a) if a > 0.0 && a <= 1.0 => Ok(a),
        _ => Err(format!(
            "--ema-alpha takes the new estimate's weight in (0, 1], not {s:?}"
        )),
    }
}

/// A count of patterns or estimates, up to `config::MAX_PATTERNS` (the refresh evaluates
/// every pattern of a pixel at once).
pub fn parse_pattern_count(s: &str) -> Result<u32, String> {
    let max = crate::config::MAX_PATTERNS;
    match s.parse::<u32>() {
        Ok(n) if (1..=max).contains(&n) => Ok(n),
        _ => Err(format!(
            "{s:?} is not a count in 1..={max} (the refresh evaluates every pattern of a pixel \
             at once)"
        )),
    }
}

pub fn parse_vpls(s: &str) -> Result<u32, String> {
    if s == "all" {
        return Ok(0);
    }
    match s.parse::<u32>() {
        Ok(n) if (1..=16384).contains(&n) => Ok(n),
        _ => Err(format!(
            "--vpls takes a count in 1..=16384 or `all`, not {s:?}"
        )),
    }
}

/// `on`/`off` (also yes/no, true/false); shared with `ssgi sweep --vary`.
/// `--render-scale`: the render size as a fraction of the window's, 0.1 to 1.
pub fn parse_render_scale(s: &str) -> std::result::Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(f) if (0.1..=1.0).contains(&f) => Ok(f),
        _ => Err(format!(
            "--render-scale takes a fraction of the window's size in 0.1..=1, not {s:?}"
        )),
    }
}

pub fn parse_on_off(s: &str) -> Result<bool, String> {
    match s {
        "on" | "yes" | "true" => Ok(true),
        "off" | "no" | "false" => Ok(false),
        _ => Err(format!("expected on or off, got {s:?}")),
    }
}

pub fn parse_epsilon(s: &str) -> Result<Epsilon, String> {
    let (abs, number) = match s.strip_prefix("abs:") {
        Some(rest) => (true, rest),
        None => (false, s),
    };
    let v: f32 = number
        .parse()
        .map_err(|_| format!("--epsilon takes a number or abs:<number>, not {s:?}"))?;
    if !(v.is_finite() && v > 0.0) {
        return Err(format!("--epsilon {s}: must be a finite positive number"));
    }
    Ok(if abs {
        Epsilon::Absolute { epsilon: v }
    } else {
        Epsilon::Relative { scale: v }
    })
}

/// An integer in `min..=max` (a sweep value's count).
pub fn parse_count(s: &str, min: u32, max: u32) -> Result<u32, String> {
    match s.parse::<u32>() {
        Ok(n) if (min..=max).contains(&n) => Ok(n),
        _ => Err(format!("not an integer in {min}..={max}")),
    }
}

/// Eq 7's attenuation coefficients `A:B` (D(d) = 1 + A d + B d^2), each finite and >= 0
/// (a colon, because a sweep's values are separated by commas).
pub fn parse_attenuation(s: &str) -> Result<[f32; 2], String> {
    let bad = || format!("not two coefficients A:B, each finite and >= 0: {s:?}");
    let (a, b) = s.split_once(':').ok_or_else(bad)?;
    let c = |x: &str| match x.trim().parse::<f32>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(bad()),
    };
    Ok([c(a)?, c(b)?])
}

/// A sampling radius as a fraction of the scene's bounding radius: in (0, 10].
pub fn parse_radius(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(r) if r.is_finite() && r > 0.0 && r <= 10.0 => Ok(r),
        _ => Err("not a number in (0, 10]".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attenuation_takes_two_finite_non_negative_coefficients() {
        assert_eq!(parse_attenuation("0:1"), Ok([0.0, 1.0]));
        assert_eq!(parse_attenuation(" 0.5 : 2 "), Ok([0.5, 2.0]));
        for bad in ["0", "0,1", "-1:0", "nan:0", "0:inf", "a:b", ":", "1:2:3"] {
            assert!(parse_attenuation(bad).is_err(), "{bad:?} accepted");
        }
    }
}

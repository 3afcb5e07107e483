//! The viewer's test script (hidden `--script` flag, for runs under Xvfb): parsing
//! `FRAME:OP,...` and handing out the steps due before each presented frame.

use crate::frontend::view_state::{display_cycle, Action};

/// One step of a scripted run (hidden `--script` flag, for tests under Xvfb): before
/// presented frame `frame`, do `op`.
#[derive(Clone, Debug, PartialEq)]
pub struct ScriptStep {
    pub frame: u64,
    pub op: ScriptOp,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ScriptOp {
    /// Ask the window system for this inner size.
    Resize(u32, u32),
    /// Behave as if the window had a zero extent (minimised) for this many event-loop
    /// iterations: X11 windows never have one (a minimised X11 window keeps its size, and a
    /// zero-sized X window is invalid), so under Xvfb the path is exercised this way.
    ZeroExtent(u32),
    /// A viewer key action by name (`Action::from_name`: cycle, pcf, an effect switch or
    /// setting, reuse, camera, help, quit).
    Key(String),
    /// Show this buffer of the display cycle by name.
    Display(String),
    /// A live setting: sweep key and value (checked when applied, as the overlay's are).
    Set(String, String),
    /// Wait for the ground-truth job (`key=truth` starts it) and score the frame.
    WaitTruth,
    /// Move the camera forward by this fraction of the scene's bounding radius (as a held
    /// `W` would).
    Move(f32),
}

/// Parse `FRAME:OP[,FRAME:OP...]` with OP one of `resize=WxH`, `zero=N`, `key=NAME`,
/// `display=NAME`, `set=KEY:VALUE`, `wait=truth`, `move=FRACTION`.
pub fn parse_script(s: &str) -> std::result::Result<Vec<ScriptStep>, String> {
    let mut steps = Vec::new();
    for part in s.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let bad = || {
            format!("bad script step {part:?}: expected FRAME:resize=WxH, FRAME:zero=N, FRAME:key=NAME, FRAME:display=NAME, FRAME:set=KEY:VALUE, FRAME:wait=truth or FRAME:move=FRACTION")
        };
        let (frame, op) = part.split_once(':').ok_or_else(bad)?;
        let frame: u64 = frame.trim().parse().map_err(|_| bad())?;
        let (name, value) = op.split_once('=').ok_or_else(bad)?;
        let op = match name.trim() {
            "resize" => {
                let (w, h) = value.split_once(['x', 'X']).ok_or_else(bad)?;
                let w: u32 = w.trim().parse().map_err(|_| bad())?;
                let h: u32 = h.trim().parse().map_err(|_| bad())?;
                if w == 0 || h == 0 {
                    return Err(format!("{part:?}: use zero=N for a zero extent"));
                }
                ScriptOp::Resize(w, h)
            }
            "zero" => ScriptOp::ZeroExtent(value.trim().parse().map_err(|_| bad())?),
            "key" => {
                let key = value.trim();
                if Action::from_name(key).is_none() {
                    return Err(format!("{part:?}: unknown key action {key:?}"));
                }
                ScriptOp::Key(key.to_string())
            }
            "display" => {
                let name = value.trim();
                if !display_cycle().iter().any(|(_, n)| *n == name) {
                    return Err(format!("{part:?}: unknown buffer {name:?}"));
                }
                ScriptOp::Display(name.to_string())
            }
            "wait" if value.trim() == "truth" => ScriptOp::WaitTruth,
            "move" => {
                let d: f32 = value.trim().parse().map_err(|_| bad())?;
                if !d.is_finite() {
                    return Err(bad());
                }
                ScriptOp::Move(d)
            }
            "set" => {
                let (key, value) = value.split_once(':').ok_or_else(bad)?;
                ScriptOp::Set(key.trim().to_string(), value.trim().to_string())
            }
            _ => return Err(bad()),
        };
        steps.push(ScriptStep { frame, op });
    }
    Ok(steps)
}

/// Remove the steps due before presented frame `frame` from `steps` and return their ops.
pub fn take_due(steps: &mut Vec<ScriptStep>, frame: u64) -> Vec<ScriptOp> {
    let due = steps
        .iter()
        .filter(|s| s.frame == frame)
        .map(|s| s.op.clone())
        .collect();
    steps.retain(|s| s.frame != frame);
    due
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn script_parses_and_rejects_nonsense() {
        let s = parse_script("10:resize=96x72, 20:zero=5,30:key=cycle").unwrap();
        assert_eq!(
            s,
            vec![
                ScriptStep {
                    frame: 10,
                    op: ScriptOp::Resize(96, 72)
                },
                ScriptStep {
                    frame: 20,
                    op: ScriptOp::ZeroExtent(5)
                },
                ScriptStep {
                    frame: 30,
                    op: ScriptOp::Key("cycle".into())
                },
            ]
        );
        assert!(parse_script("10:resize=0x5").is_err());
        assert!(parse_script("x:zero=1").is_err());
        assert!(parse_script("1:key=explode").is_err());
        assert!(parse_script("1:fly=1").is_err());
        assert_eq!(
            parse_script("4:set=ao.estimator:gtao").unwrap()[0].op,
            ScriptOp::Set("ao.estimator".into(), "gtao".into())
        );
        assert!(parse_script("4:set=ao.estimator").is_err());
        assert_eq!(
            parse_script("5:wait=truth,6:move=-0.5").unwrap()[1].op,
            ScriptOp::Move(-0.5)
        );
        assert!(parse_script("5:wait=frames").is_err());
        assert!(parse_script("6:move=nan").is_err());
    }

    #[test]
    fn due_steps_are_taken_once() {
        let mut s = parse_script("3:key=help,5:zero=2,3:display=ao").unwrap();
        assert_eq!(take_due(&mut s, 0), vec![]);
        assert_eq!(
            take_due(&mut s, 3),
            vec![ScriptOp::Key("help".into()), ScriptOp::Display("ao".into())]
        );
        assert_eq!(take_due(&mut s, 3), vec![]);
        assert_eq!(s.len(), 1);
    }
}

//! The frame as data (`ssgi bench --explain`): every pass one frame records, in recording
//! order, with the images and buffers its declaration reads and writes (the same table its
//! barriers come from: `passes::decl::access` logs each use while the tracker declares), then
//! the passes the frame left out and why.

use crate::vk::sync::Declared;
use crate::vk::Skipped;

/// One pass's line: its resources in declaration order, each once.
fn pass_line(pass: &str, uses: &[&Declared]) -> String {
    let names = |pick: fn(&Declared) -> bool| {
        let mut out: Vec<&str> = Vec::new();
        for u in uses.iter().filter(|u| pick(u)) {
            if !out.contains(&u.resource.as_str()) {
                out.push(&u.resource);
            }
        }
        out.join(", ")
    };
    let parts = [
        ("reads", names(|u| u.reads && !u.writes)),
        ("writes", names(|u| u.writes && !u.reads)),
        ("updates", names(|u| u.reads && u.writes)),
    ];
    let said: Vec<String> = parts
        .iter()
        .filter(|(_, list)| !list.is_empty())
        .map(|(verb, list)| format!("{verb} {list}"))
        .collect();
    format!("{pass:<20} {}\n", said.join("; "))
}

/// The frame's passes from its declared uses (consecutive uses of one pass are one line; a
/// pass recorded twice shows twice), then the skipped passes with their reasons.
pub fn describe(declared: &[Declared], skipped: &[Skipped]) -> String {
    let mut out = String::new();
    let mut start = 0;
    while start < declared.len() {
        let pass = &declared[start].pass;
        let end = declared[start..]
            .iter()
            .position(|d| &d.pass != pass)
            .map_or(declared.len(), |n| start + n);
        let uses: Vec<&Declared> = declared[start..end].iter().collect();
        out += &pass_line(pass, &uses);
        start = end;
    }
    for s in skipped {
        out += &format!("{:<20} skipped ({})\n", s.pass, s.reason.name());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vk::SkipReason;

    fn d(pass: &str, resource: &str, reads: bool, writes: bool) -> Declared {
        Declared {
            pass: pass.into(),
            resource: resource.into(),
            reads,
            writes,
        }
    }

    #[test]
    fn one_line_per_recorded_pass_with_reads_writes_and_updates_apart() {
        let declared = [
            d("gbuffer", "g.position", false, true),
            d("gbuffer", "g.normal", false, true),
            d("ssao", "g.position", true, false),
            d("ssao", "ao.history", true, true),
            d("ssao", "g.position", true, false),
            d("composite", "ao.history", true, false),
            d("composite", "output", false, true),
            d("ssao", "ao.history", true, true),
        ];
        let skipped = [Skipped {
            pass: "light_view",
            reason: SkipReason::Unchanged,
        }];
        let text = describe(&declared, &skipped);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(
            lines,
            [
                format!("{:<20} writes g.position, g.normal", "gbuffer"),
                format!("{:<20} reads g.position; updates ao.history", "ssao"),
                format!("{:<20} reads ao.history; writes output", "composite"),
                format!("{:<20} updates ao.history", "ssao"),
                format!("{:<20} skipped (unchanged)", "light_view"),
            ]
        );
    }
}

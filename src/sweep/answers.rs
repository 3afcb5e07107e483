//! The answer a sweep's reader came for: for one buffer, which combination is the most accurate
//! within each GPU time budget, i.e. its Pareto front read from the fastest row up. Rendered
//! as a Markdown table from a written sweep.json, so that a statement in the README is
//! regenerated from the measurement instead of typed (`tests/readme_answers.rs` compares the
//! README's blocks with this; `cargo run --example readme_answers` rewrites them).

use super::time_from;
use crate::bench::measure::Buffer;
use crate::error::{Error, Result};
use serde_json::Value;

/// One step of the front: from `from_ms` on, `label` is the most accurate combination.
#[derive(Clone, Debug, PartialEq)]
pub struct Answer {
    pub from_ms: f64,
    pub label: String,
    pub error: f64,
}

fn bad(what: String) -> Error {
    Error::Config(format!("sweep.json: {what}"))
}

/// `buffer`'s Pareto front in `sweep` (a sweep.json), fastest first: the rows marked on it,
/// each with its time on the buffer's axis and its error against the ground truth (FLIP for
/// the final image, RMSE otherwise).
pub fn answers(sweep: &Value, buffer: &str) -> Result<Vec<Answer>> {
    let b = Buffer::ALL
        .into_iter()
        .find(|b| b.name() == buffer)
        .ok_or_else(|| bad(format!("no buffer called {buffer:?}")))?;
    let rows = sweep["rows"]
        .as_array()
        .ok_or_else(|| bad("no rows".into()))?;
    let mut front = Vec::new();
    for row in rows.iter().filter(|r| r["pareto"][buffer] == true) {
        let ms = time_from(|g| row["ms"][g].as_f64(), b)
            .ok_or_else(|| bad(format!("a row on {buffer}'s front has no time")))?;
        let e = &row["truth"][buffer];
        let error = match b {
            Buffer::Final => e["flip"].as_f64(),
            _ => e["rmse"].as_f64(),
        }
        .ok_or_else(|| bad(format!("a row on {buffer}'s front has no error")))?;
        let pairs: Vec<String> = row["label"]
            .as_array()
            .map(|l| {
                l.iter()
                    .filter_map(|kv| Some(format!("{}={}", kv[0].as_str()?, kv[1].as_str()?)))
                    .collect()
            })
            .unwrap_or_default();
        let label = if pairs.is_empty() {
            "base".to_string()
        } else {
            pairs.join(", ")
        };
        front.push(Answer {
            from_ms: ms,
            label,
            error,
        });
    }
    front.sort_by(|a, c| a.from_ms.total_cmp(&c.from_ms));
    Ok(front)
}

/// The front of `buffer` as a Markdown table under a line naming the sweep's scene, size,
/// path and device: one row per time budget.
pub fn markdown(sweep: &Value, buffer: &str) -> Result<String> {
    let front = answers(sweep, buffer)?;
    let h = &sweep["header"];
    let size = |i: usize| h["size"][i].as_u64().unwrap_or(0);
    let metric = if buffer == "final" { "FLIP" } else { "RMSE" };
    let mut md = format!(
        "{} at {}x{} along `{}`, {} (driver {}):\n\n| GPU time budget ({buffer}) | most \
         accurate within it | {buffer} {metric} against the ground truth |\n|---|---|---|\n",
        h["scene"].as_str().unwrap_or("?"),
        size(0),
        size(1),
        h["path"].as_str().unwrap_or("?"),
        h["device"].as_str().unwrap_or("?"),
        h["driver"].as_str().unwrap_or("?"),
    );
    for a in &front {
        md += &format!(
            "| from {:.3} ms | {} | {:.4} |\n",
            a.from_ms, a.label, a.error
        );
    }
    Ok(md)
}

/// The opening of a generated block: `<!-- answers: PATH BUFFER -->`, PATH a sweep.json
/// relative to the document's root.
const OPEN: &str = "<!-- answers: ";
const CLOSE: &str = "<!-- /answers -->";

/// `text` with every answers block regenerated from the sweep.json it names (paths relative to
/// `root`), and how many blocks there were.
pub fn rewrite_blocks(text: &str, root: &std::path::Path) -> Result<(String, usize)> {
    let mut out = String::new();
    let mut rest = text;
    let mut blocks = 0;
    while let Some(start) = rest.find(OPEN) {
        let header_end = rest[start..]
            .find("-->")
            .map(|i| start + i + 3)
            .ok_or_else(|| bad("an answers block's opening is not closed".into()))?;
        let spec = rest[start + OPEN.len()..header_end - 3].trim();
        let (path, buffer) = spec
            .rsplit_once(' ')
            .ok_or_else(|| bad(format!("answers block {spec:?}: give PATH BUFFER")))?;
        let end = rest[header_end..]
            .find(CLOSE)
            .map(|i| header_end + i)
            .ok_or_else(|| bad(format!("answers block {spec:?} has no {CLOSE}")))?;
        let file = root.join(path);
        let json =
            std::fs::read_to_string(&file).map_err(|e| bad(format!("{}: {e}", file.display())))?;
        let sweep: Value =
            serde_json::from_str(&json).map_err(|e| bad(format!("{}: {e}", file.display())))?;
        out += &rest[..header_end];
        out += "\n";
        out += &markdown(&sweep, buffer)?;
        out += CLOSE;
        rest = &rest[end + CLOSE.len()..];
        blocks += 1;
    }
    out += rest;
    Ok((out, blocks))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_front_reads_fastest_first_with_each_rows_time_and_error() {
        let sweep = serde_json::json!({
            "header": { "scene": "s", "size": [8, 4], "path": "p", "device": "d", "driver": "v" },
            "rows": [
                { "label": [["ao.estimator", "gtao"]], "ms": { "ao": 2.0 },
                  "truth": { "ao": { "rmse": 0.1 } }, "pareto": { "ao": true } },
                { "label": [["ao.estimator", "crytek"]], "ms": { "ao": 1.5 },
                  "truth": { "ao": { "rmse": 0.4 } }, "pareto": { "ao": false } },
                { "label": [["ao.estimator", "thesis"]], "ms": { "ao": 1.0 },
                  "truth": { "ao": { "rmse": 0.2 } }, "pareto": { "ao": true } }
            ]
        });
        let a = answers(&sweep, "ao").unwrap();
        let labels: Vec<&str> = a.iter().map(|a| a.label.as_str()).collect();
        assert_eq!(labels, ["ao.estimator=thesis", "ao.estimator=gtao"]);
        assert_eq!((a[0].from_ms, a[0].error), (1.0, 0.2));
        let md = markdown(&sweep, "ao").unwrap();
        assert!(md.starts_with("s at 8x4 along `p`, d (driver v)"), "{md}");
        assert!(
            md.contains("| from 2.000 ms | ao.estimator=gtao | 0.1000 |"),
            "{md}"
        );
        assert!(answers(&sweep, "nothing").is_err());
    }
}

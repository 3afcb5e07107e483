//! Where a key sits in a TOML text (scene files, keyframe files): serde reports a value's byte
//! offset or nothing, and checks after parsing report a table, an index and a key; both are
//! turned into the line (1-based) and the dotted key a user looks for.

/// The header (`camera`, `mesh`) a line opens, if it is one.
fn header(line: &str) -> Option<&str> {
    let t = line.trim();
    let inner = t.strip_prefix("[[").and_then(|s| s.split("]]").next());
    inner
        .or_else(|| t.strip_prefix('[').and_then(|s| s.split(']').next()))
        .map(str::trim)
}

/// The key a `key = value` line sets.
fn line_key(line: &str) -> Option<&str> {
    let (key, _) = line.split_once('=')?;
    let key = key.trim().trim_matches('"');
    (!key.is_empty() && !key.starts_with('#')).then_some(key)
}

/// Line (1-based) and dotted key at byte `offset` of `text`: the table the line sits in and
/// the key it sets.
pub fn key_at(text: &str, offset: usize) -> (Option<usize>, String) {
    let offset = offset.min(text.len());
    let before = text.get(..offset).unwrap_or(text);
    let line_no = before.matches('\n').count();
    let mut table = String::new();
    let mut key = String::new();
    for (i, line) in text.lines().enumerate().take(line_no + 1) {
        if let Some(h) = header(line) {
            table = h.to_owned();
            key.clear();
        } else if i == line_no {
            key = line_key(line).unwrap_or_default().to_owned();
        }
    }
    let dotted = match (table.is_empty(), key.is_empty()) {
        (true, _) => key,
        (false, true) => table,
        (false, false) => format!("{table}.{key}"),
    };
    (Some(line_no + 1), dotted)
}

/// Line and dotted key of `key` in the `index`-th `table` (`""`: the top level). The table's
/// header line when the key is not written; no line when the table is not there either.
pub fn locate(text: &str, table: &str, index: usize, key: &str) -> (Option<usize>, String) {
    let mut seen = 0usize;
    let mut in_table = table.is_empty();
    let mut header_line = None;
    for (i, line) in text.lines().enumerate() {
        if let Some(h) = header(line) {
            in_table = h == table && {
                seen += 1;
                seen == index + 1
            };
            if in_table {
                header_line = Some(i + 1);
            }
            continue;
        }
        if in_table && line_key(line) == Some(key) {
            return (Some(i + 1), dotted(table, index, key));
        }
    }
    (header_line, dotted(table, index, key))
}

fn dotted(table: &str, index: usize, key: &str) -> String {
    match table {
        "" => key.to_owned(),
        // `keyframes`: a keyframe file's (`path.rs`), located by the same rules.
        "mesh" | "camera_keyframes" | "light_keyframes" | "mesh.keyframes" | "keyframes" => {
            format!("{table}[{index}].{key}")
        }
        _ => format!("{table}.{key}"),
    }
}

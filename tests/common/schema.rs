//! The JSON report formats of docs/formats.md, checked against reports the program wrote.
//!
//! A format is a ```text block right after a `<!-- schema: NAME -->` line of docs/formats.md,
//! in its notation: `{ "key", "key": value, ... }` (an object: every key listed must be
//! there, and no other unless the object has `...` or a `"<name>": value` entry, which every
//! other key's value must then follow; a key ending in `?` may be absent), `[ value ]` (an
//! array whose elements each follow `value`), `<NAME report>` (another format by name), a
//! number or a "string" (that exact value), or a word (any value, null included). An object,
//! array or report followed by `| null` may also be null; without it null is an error.
//! `//` starts a comment.

use serde_json::Value;
use std::collections::BTreeMap;

#[derive(Debug, Clone)]
pub enum Schema {
    Object {
        keys: Vec<(String, bool, Schema)>,
        wildcard: Option<Box<Schema>>,
        open: bool,
    },
    Array(Box<Schema>),
    Ref(String),
    /// `value | null`: that value, or null (an object, array or report may be null only so).
    Nullable(Box<Schema>),
    Exact(Value),
    Any,
}

/// Every format of docs/formats.md by name.
pub fn documented_schemas() -> BTreeMap<String, Schema> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/formats.md");
    let text = std::fs::read_to_string(path).expect("docs/formats.md");
    let mut out = BTreeMap::new();
    let mut lines = text.lines();
    while let Some(line) = lines.next() {
        let Some(name) = line
            .trim()
            .strip_prefix("<!-- schema:")
            .and_then(|r| r.strip_suffix("-->"))
        else {
            continue;
        };
        let name = name.trim().to_string();
        assert_eq!(
            lines.next().map(str::trim),
            Some("```text"),
            "docs/formats.md schema {name}: a ```text block must follow its marker"
        );
        let body: Vec<&str> = lines.by_ref().take_while(|l| l.trim() != "```").collect();
        let body: String = body
            .iter()
            .map(|l| l.split("//").next().unwrap())
            .collect::<Vec<_>>()
            .join("\n");
        let mut p = Parser {
            chars: body.chars().collect(),
            at: 0,
        };
        let schema = p.value();
        p.skip_ws();
        assert!(
            p.at == p.chars.len(),
            "docs/formats.md schema {name}: unexpected text at {}",
            p.rest()
        );
        out.insert(name, schema);
    }
    out
}

struct Parser {
    chars: Vec<char>,
    at: usize,
}

impl Parser {
    fn skip_ws(&mut self) {
        while self.chars.get(self.at).is_some_and(|c| c.is_whitespace()) {
            self.at += 1;
        }
    }

    fn peek(&mut self) -> Option<char> {
        self.skip_ws();
        self.chars.get(self.at).copied()
    }

    fn rest(&self) -> String {
        self.chars[self.at.min(self.chars.len())..]
            .iter()
            .take(40)
            .collect()
    }

    fn eat(&mut self, c: char) -> bool {
        if self.peek() == Some(c) {
            self.at += 1;
            true
        } else {
            false
        }
    }

    fn string(&mut self) -> String {
        assert!(self.eat('"'), "expected a string at {}", self.rest());
        let start = self.at;
        while self.chars.get(self.at).is_some_and(|&c| c != '"') {
            self.at += 1;
        }
        let s: String = self.chars[start..self.at].iter().collect();
        self.at += 1;
        s
    }

    /// A value, and ` | null` after an object, array or report where the format allows null.
    fn value(&mut self) -> Schema {
        let s = self.plain_value();
        self.skip_ws();
        let rest: String = self.chars[self.at..].iter().take(6).collect();
        if rest == "| null" {
            self.at += 6;
            return Schema::Nullable(Box::new(s));
        }
        s
    }

    fn plain_value(&mut self) -> Schema {
        match self.peek() {
            Some('{') => self.object(),
            Some('[') => {
                self.at += 1;
                let mut items = Vec::new();
                while !self.eat(']') {
                    items.push(self.value());
                    self.eat(',');
                }
                // One object or format: every element follows it; literals: any array.
                match items.into_iter().next() {
                    Some(s @ (Schema::Object { .. } | Schema::Ref(_))) => {
                        Schema::Array(Box::new(s))
                    }
                    _ => Schema::Array(Box::new(Schema::Any)),
                }
            }
            Some('"') => Schema::Exact(Value::String(self.string())),
            Some('<') => {
                let start = self.at;
                while self.chars.get(self.at).is_some_and(|&c| c != '>') {
                    self.at += 1;
                }
                self.at += 1;
                let inner: String = self.chars[start + 1..self.at - 1].iter().collect();
                match inner.strip_suffix(" report") {
                    Some(name) => Schema::Ref(name.trim().to_string()),
                    None => Schema::Any,
                }
            }
            _ => {
                let start = self.at;
                while self
                    .chars
                    .get(self.at)
                    .is_some_and(|&c| !matches!(c, ',' | '}' | ']'))
                {
                    self.at += 1;
                }
                let word: String = self.chars[start..self.at].iter().collect();
                match word.trim().parse::<f64>() {
                    Ok(n) => Schema::Exact(serde_json::json!(n)),
                    Err(_) => Schema::Any,
                }
            }
        }
    }

    fn object(&mut self) -> Schema {
        assert!(self.eat('{'));
        let (mut keys, mut wildcard, mut open) = (Vec::new(), None, false);
        while !self.eat('}') {
            if self.peek() == Some('.') {
                while self.chars.get(self.at) == Some(&'.') {
                    self.at += 1;
                }
                open = true;
            } else {
                let key = self.string();
                let optional = self.eat('?');
                let value = if self.eat(':') {
                    self.value()
                } else {
                    Schema::Any
                };
                if key.starts_with('<') {
                    wildcard = Some(Box::new(value));
                } else {
                    keys.push((key, optional, value));
                }
            }
            self.eat(',');
        }
        Schema::Object {
            keys,
            wildcard,
            open,
        }
    }
}

/// Where `value` departs from docs/formats.md's format `name` (empty: it follows it).
pub fn check(name: &str, value: &Value) -> Vec<String> {
    let all = documented_schemas();
    let schema = all
        .get(name)
        .unwrap_or_else(|| panic!("docs/formats.md has no <!-- schema: {name} --> block"));
    let mut errors = Vec::new();
    walk(&all, schema, value, name, &mut errors);
    errors
}

/// Panics, listing every difference, unless `value` follows docs/formats.md's format `name`.
pub fn assert_follows(name: &str, value: &Value) {
    let errors = check(name, value);
    assert!(
        errors.is_empty(),
        "the report departs from docs/formats.md's {name} format:\n{}",
        errors.join("\n")
    );
}

fn walk(
    all: &BTreeMap<String, Schema>,
    schema: &Schema,
    value: &Value,
    at: &str,
    errors: &mut Vec<String>,
) {
    match schema {
        Schema::Any => {}
        Schema::Exact(want) => {
            let same = match (want.as_f64(), value.as_f64()) {
                (Some(a), Some(b)) => a == b,
                _ => want == value,
            };
            if !same {
                errors.push(format!("{at}: {value} where docs/formats.md says {want}"));
            }
        }
        Schema::Ref(name) => {
            let s = all
                .get(name)
                .unwrap_or_else(|| panic!("docs/formats.md has no <!-- schema: {name} --> block"));
            walk(all, s, value, at, errors);
        }
        Schema::Nullable(_) if value.is_null() => {}
        Schema::Nullable(s) => walk(all, s, value, at, errors),
        Schema::Array(item) => match value.as_array() {
            Some(items) => {
                for (i, v) in items.iter().enumerate() {
                    walk(all, item, v, &format!("{at}[{i}]"), errors);
                }
            }
            None => errors.push(format!("{at}: not an array ({value})")),
        },
        Schema::Object {
            keys,
            wildcard,
            open,
        } => {
            let Some(map) = value.as_object() else {
                errors.push(format!("{at}: not an object ({value})"));
                return;
            };
            for (key, optional, s) in keys {
                match map.get(key) {
                    Some(v) => walk(all, s, v, &format!("{at}.{key}"), errors),
                    None if *optional => {}
                    None => errors.push(format!("{at}.{key}: documented, not in the report")),
                }
            }
            for (key, v) in map {
                if keys.iter().any(|(k, ..)| k == key) {
                    continue;
                }
                match wildcard {
                    Some(s) => walk(all, s, v, &format!("{at}.{key}"), errors),
                    None if *open => {}
                    None => errors.push(format!("{at}.{key}: in the report, not documented")),
                }
            }
        }
    }
}

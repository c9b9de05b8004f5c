//! Where in a JSON text a serde_json error is: the path of keys and indices
//! (`front.damper`, `[1].mass`) at the error's line and column.
//!
//! serde_json reports every error at a position in the text: after the value of the wrong
//! type, after an unknown key, at the closing brace of an object that lacks a field,
//! inside a number out of range. The path at that position is the field at fault. Found
//! this way, after the fact, by one small scanner, it costs nothing when the text is
//! good, and each type's reader is compiled once (serde_path_to_error, which tracked the
//! path on every read, compiled a second reader per type: 13.8 KB of the page's
//! first-screen module before gzip, issue #29).

use serde::de::DeserializeOwned;

/// `T` read from `text`; an error comes with the path of the field at fault (`""` for
/// the text as a whole).
pub(crate) fn from_str<T: DeserializeOwned>(text: &str) -> Result<T, (String, serde_json::Error)> {
    serde_json::from_str(text).map_err(|e| (path_at(text, e.line(), e.column()), e))
}

/// A frame of the scanner: an object with the key whose value is being read, or an array
/// with the index of the item being read.
enum Frame {
    Object(Option<String>),
    Array(usize),
}

/// The path at `line` and `column` (1-based, bytes, as serde_json counts them) of the
/// JSON text `text`: the keys and indices of the values open there, `""` at the top. At a
/// closing brace or bracket (just after it, where serde_json reports a missing field),
/// the path is the object's or array's own.
pub(crate) fn path_at(text: &str, line: usize, column: usize) -> String {
    let bytes = text.as_bytes();
    let line_start = match line {
        0 | 1 => 0,
        n => bytes
            .iter()
            .enumerate()
            .filter(|&(_, &b)| b == b'\n')
            .nth(n - 2)
            .map_or(bytes.len(), |(i, _)| i + 1),
    };
    let mut end = (line_start + column).min(bytes.len());
    // Just after a closing brace: the error is about that object itself.
    let closing = end > 0 && matches!(bytes[end - 1], b'}' | b']');
    // At a comma it did not expect (`[1,, 2]`): the item that comma should have begun
    // is missing, and the path is that item's.
    if closing || (end > 0 && bytes[end - 1] == b',') {
        end -= 1;
    }
    let mut frames: Vec<Frame> = Vec::new();
    // An object expects a key after `{` and `,`; any other string is a value.
    let mut expect_key = false;
    let mut i = 0;
    while i < end {
        match bytes[i] {
            b'"' => {
                let start = i + 1;
                i += 1;
                while i < bytes.len() && bytes[i] != b'"' {
                    i += if bytes[i] == b'\\' { 2 } else { 1 };
                }
                // A key cut short by the error (`{"na`) is no field yet.
                if expect_key && i < end {
                    if let Some(Frame::Object(key)) = frames.last_mut() {
                        *key = Some(
                            text.get(start..i.min(bytes.len()))
                                .unwrap_or("")
                                .to_string(),
                        );
                    }
                    expect_key = false;
                }
            }
            b'{' => {
                frames.push(Frame::Object(None));
                expect_key = true;
            }
            b'[' => {
                frames.push(Frame::Array(0));
                expect_key = false;
            }
            b'}' | b']' => {
                frames.pop();
                expect_key = false;
            }
            b',' => match frames.last_mut() {
                Some(Frame::Object(key)) => {
                    *key = None;
                    expect_key = true;
                }
                Some(Frame::Array(k)) => *k += 1,
                None => {}
            },
            _ => {}
        }
        i += 1;
    }
    if closing {
        // The closed object's or array's own path: not its last key or item.
        match frames.last_mut() {
            Some(Frame::Object(key)) => *key = None,
            Some(Frame::Array(_)) => {
                frames.pop();
            }
            None => {}
        }
    }
    join(&frames)
}

/// The frames as a path: `key.key[i].key`.
fn join(frames: &[Frame]) -> String {
    let mut path = String::new();
    for f in frames {
        match f {
            Frame::Object(Some(key)) => {
                if !path.is_empty() {
                    path.push('.');
                }
                path.push_str(key);
            }
            Frame::Object(None) => {}
            Frame::Array(k) => path.push_str(&format!("[{k}]")),
        }
    }
    path
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Axle {
        spring: f64,
        damper: f64,
    }

    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Car {
        name: String,
        mass: f64,
        front: Axle,
        loads: Vec<Axle>,
    }

    fn path_of(text: &str) -> String {
        from_str::<Car>(text).unwrap_err().0
    }

    /// The paths serde_path_to_error gave for each kind of error, from the text alone.
    #[test]
    fn each_kind_of_error_is_found_at_its_field() {
        let ok = r#"{"name": "a", "mass": 1, "front": {"spring": 1, "damper": 2}, "loads": [{"spring": 1, "damper": 2}]}"#;
        assert!(from_str::<Car>(ok).is_ok());
        // A value of the wrong type, at the top, nested, in an array's item.
        assert_eq!(
            path_of(&ok.replace(r#""mass": 1"#, r#""mass": "one""#)),
            "mass"
        );
        assert_eq!(
            path_of(&ok.replace(r#""damper": 2}, "loads""#, r#""damper": "x"}, "loads""#)),
            "front.damper"
        );
        let second = ok.replace(
            r#"[{"spring": 1, "damper": 2}]"#,
            r#"[{"spring": 1, "damper": 2}, {"spring": true, "damper": 2}]"#,
        );
        assert_eq!(path_of(&second), "loads[1].spring");
        // An unknown key; a missing field (the object that lacks it; the top: "").
        assert_eq!(
            path_of(&ok.replace(r#""mass": 1"#, r#""mass": 1, "colour": 2"#)),
            "colour"
        );
        assert_eq!(
            path_of(&ok.replace(
                r#"{"spring": 1, "damper": 2}, "loads""#,
                r#"{"spring": 1}, "loads""#
            )),
            "front"
        );
        let item = ok.replace(
            r#"[{"spring": 1, "damper": 2}]"#,
            r#"[{"spring": 1, "damper": 2},, ]"#,
        );
        assert_eq!(path_of(&item), "loads[1]");
        assert_eq!(path_of(r#"{"name": "a", "mass"#), "");
        assert_eq!(path_of(&ok.replace(r#""mass": 1, "#, "")), "");
        // A number out of range, a key with an escaped quote, text over several lines.
        assert_eq!(
            path_of(&ok.replace(r#""mass": 1"#, r#""mass": 1e999"#)),
            "mass"
        );
        let escaped = ok.replace(r#""name": "a""#, r#""name": "a \"b\" {[,", "x\"y": 1"#);
        assert_eq!(path_of(&escaped), "x\\\"y");
        let lines = ok
            .replacen(r#""spring": 1, "#, r#""spring": null, "#, 1)
            .replace(", ", ",\n  ")
            .replace(r#""damper": "#, "\"damper\":\n ");
        assert_eq!(path_of(&lines), "front.spring");
        // Not JSON: where it breaks.
        assert_eq!(
            path_of(r#"{"name": "a", "front": {"spring": 1,, }"#),
            "front"
        );
    }
}

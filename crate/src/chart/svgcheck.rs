//! A small reader of the SVG the charts write, for tests: checks that tags nest and
//! close, and lists the elements with their attributes and text.

use std::collections::HashMap;

/// One element: tag name, attributes, and its text (for `<text>`).
#[derive(Debug, Clone)]
pub(crate) struct Element {
    pub name: String,
    pub attrs: HashMap<String, String>,
    pub text: String,
}

impl Element {
    pub(crate) fn attr(&self, key: &str) -> &str {
        self.attrs.get(key).map(String::as_str).unwrap_or("")
    }

    pub fn num(&self, key: &str) -> f64 {
        self.attr(key)
            .parse()
            .unwrap_or_else(|_| panic!("<{}> {key}={:?}", self.name, self.attr(key)))
    }

    /// The `points` of a polyline or polygon.
    pub fn points(&self) -> Vec<(f64, f64)> {
        self.attr("points")
            .split_whitespace()
            .map(|p| {
                let (x, y) = p.split_once(',').expect("x,y");
                (x.parse().unwrap(), y.parse().unwrap())
            })
            .collect()
    }
}

fn unescape(s: &str) -> String {
    s.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

/// Parses `svg`; panics (failing the test) unless it is one `<svg>` root whose tags all
/// nest and close.
pub fn parse(svg: &str) -> Vec<Element> {
    assert!(svg.starts_with("<svg "), "does not start with <svg");
    let mut out: Vec<Element> = Vec::new();
    let mut stack: Vec<(String, usize)> = Vec::new();
    let mut rest = svg;
    let mut closed_root = false;
    while let Some(start) = rest.find('<') {
        let text = &rest[..start];
        if let Some(&(_, idx)) = stack.last() {
            out[idx].text.push_str(&unescape(text.trim()));
        } else {
            assert!(text.trim().is_empty(), "text outside the root: {text:?}");
        }
        let end = rest[start..].find('>').expect("unclosed <") + start;
        let tag = &rest[start + 1..end];
        rest = &rest[end + 1..];
        assert!(!closed_root, "content after </svg>");
        if let Some(name) = tag.strip_prefix('/') {
            let (open, _) = stack.pop().expect("close without open");
            assert_eq!(open, name.trim(), "</{name}> closes <{open}>");
            if stack.is_empty() {
                closed_root = true;
            }
            continue;
        }
        let self_closing = tag.ends_with('/');
        let body = tag.trim_end_matches('/');
        let (name, mut attrs_text) = body.split_once(' ').unwrap_or((body, ""));
        let mut attrs = HashMap::new();
        loop {
            attrs_text = attrs_text.trim_start();
            if attrs_text.is_empty() {
                break;
            }
            let eq = attrs_text.find("=\"").expect("attribute without =\"");
            let key = attrs_text[..eq].to_string();
            let after = &attrs_text[eq + 2..];
            let q = after.find('"').expect("unterminated attribute");
            assert!(
                attrs.insert(key.clone(), unescape(&after[..q])).is_none(),
                "attribute {key} twice"
            );
            attrs_text = &after[q + 1..];
        }
        if stack.is_empty() {
            assert!(name == "svg" && out.is_empty(), "<{name}> outside the root");
        }
        out.push(Element {
            name: name.to_string(),
            attrs,
            text: String::new(),
        });
        if !self_closing {
            stack.push((name.to_string(), out.len() - 1));
        }
    }
    assert!(stack.is_empty(), "unclosed tags: {stack:?}");
    assert!(closed_root, "no </svg>");
    assert!(rest.trim().is_empty(), "trailing text");
    out
}

/// The elements named `name`.
pub fn all<'a>(els: &'a [Element], name: &str) -> Vec<&'a Element> {
    els.iter().filter(|e| e.name == name).collect()
}

/// The texts of the `<text>` elements.
pub(crate) fn texts(els: &[Element]) -> Vec<String> {
    all(els, "text").iter().map(|e| e.text.clone()).collect()
}

/// The largest distance, px, from a point of `points` to the polyline `line`.
pub(crate) fn farthest_from(points: &[(f64, f64)], line: &[(f64, f64)]) -> f64 {
    let to_segment = |r: (f64, f64), p: (f64, f64), q: (f64, f64)| {
        let (dx, dy) = (q.0 - p.0, q.1 - p.1);
        let l2 = dx * dx + dy * dy;
        let t = if l2 > 0.0 {
            (((r.0 - p.0) * dx + (r.1 - p.1) * dy) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (r.0 - p.0 - t * dx).hypot(r.1 - p.1 - t * dy)
    };
    points
        .iter()
        .map(|&r| {
            line.windows(2)
                .map(|w| to_segment(r, w[0], w[1]))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

/// The JSON keys a value serialises with, sorted (to compare with a spec's field list).
pub fn keys<T: serde::Serialize>(v: &T) -> Vec<String> {
    let mut k: Vec<String> = serde_json::to_value(v)
        .unwrap()
        .as_object()
        .unwrap()
        .keys()
        .cloned()
        .collect();
    k.sort();
    k
}

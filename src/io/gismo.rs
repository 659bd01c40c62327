//! G+Smo XML documents read by a real XML parser (roxmltree): comments, CDATA sections, entities
//! and character references are handled as XML defines them, and the patches of a document are
//! found the way G+Smo finds them — the `<patches>` of its first `<MultiPatch>`, which name
//! geometries by their `id` (`type="id_range"`: first and last id; `type="id_index"`: a list of
//! ids), or else every `<Geometry>` of the document in file order.

use roxmltree::{Document, Node};

use crate::error::{Error, Result};

/// Parses an XML document; a syntax error is an [`ErrorKind::Io`](crate::ErrorKind::Io) error
/// with its line and column.
pub fn parse(text: &str) -> Result<Document<'_>> {
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    Document::parse_with_options(text, options).map_err(|e| Error::io(format!("not XML: {e}")))
}

/// The line (from 1) where `node` starts.
pub fn line(node: Node<'_, '_>) -> u32 {
    node.document().text_pos_at(node.range().start).row
}

/// The text of `node`: its text and CDATA children joined (comments and child elements left
/// out), entities resolved.
pub fn text(node: Node<'_, '_>) -> String {
    node.children()
        .filter(|c| c.is_text())
        .filter_map(|c| c.text())
        .collect()
}

/// The numbers of `node`'s text; `what` names them in the message.
pub fn numbers(node: Node<'_, '_>, what: &str) -> Result<Vec<f64>> {
    let line = line(node);
    text(node)
        .split_whitespace()
        .map(|t| {
            t.parse::<f64>()
                .map_err(|_| Error::io(format!("line {line}: {what}: '{t}' is not a number")))
        })
        .collect()
}

/// The element children of `node` called `name`, in file order.
pub fn children<'a, 'input: 'a>(
    node: Node<'a, 'input>,
    name: &'a str,
) -> impl Iterator<Item = Node<'a, 'input>> + 'a {
    node.children()
        .filter(move |c| c.is_element() && c.has_tag_name(name))
}

/// The elements called `name` inside `node` (at any depth, in file order), not looking into
/// nested `<Geometry>` elements, which belong to another patch.
pub fn descendants<'a, 'input: 'a>(node: Node<'a, 'input>, name: &str) -> Vec<Node<'a, 'input>> {
    let mut out = Vec::new();
    for child in node.children().filter(|c| c.is_element()) {
        if child.has_tag_name(name) {
            out.push(child);
        } else if !child.has_tag_name("Geometry") {
            out.extend(descendants(child, name));
        }
    }
    out
}

/// The patches of a G+Smo document: the geometries its first `<MultiPatch>` names, in the order
/// of its `<patches>`, or, without a `<MultiPatch>`, every `<Geometry>` not nested in another
/// one, in file order.
pub fn patches<'a, 'input>(doc: &'a Document<'input>) -> Result<Vec<Node<'a, 'input>>> {
    let all = descendants(doc.root(), "Geometry");
    let Some(multipatch) = doc
        .descendants()
        .find(|n| n.is_element() && n.has_tag_name("MultiPatch"))
    else {
        return Ok(all);
    };
    let line = line(multipatch);
    let list = children(multipatch, "patches").next().ok_or_else(|| {
        Error::io(format!(
            "line {line}: <MultiPatch> has no <patches> element"
        ))
    })?;
    let ids = numbers(list, "patches")?;
    let ids: Vec<i64> = match list.attribute("type") {
        Some("id_range") => match ids[..] {
            [first, last] if first <= last => (first as i64..=last as i64).collect(),
            _ => {
                return Err(Error::io(format!(
                    "line {line}: <patches type=\"id_range\"> needs a first and a last id"
                )))
            }
        },
        Some("id_index") => ids.iter().map(|&v| v as i64).collect(),
        other => {
            return Err(Error::io(format!(
                "line {line}: <patches type=\"{}\"> is not supported (id_range or id_index)",
                other.unwrap_or("")
            )))
        }
    };
    ids.iter()
        .map(|&id| {
            all.iter()
                .copied()
                .find(|g| g.attribute("id").and_then(|v| v.trim().parse().ok()) == Some(id))
                .ok_or_else(|| {
                    Error::io(format!(
                        "line {line}: <MultiPatch> names Geometry id {id}, which the file does not have"
                    ))
                })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_joins_cdata_and_resolves_entities() {
        let doc = parse("<a>1 <!-- 9 --><![CDATA[2 ]]>&#51;<b>4</b></a>").unwrap();
        assert_eq!(numbers(doc.root_element(), "x").unwrap(), [1.0, 2.0, 3.0]);
    }

    #[test]
    fn patches_follow_the_multipatch_references() {
        let doc = parse(
            "<xml><Geometry id=\"2\"/><!-- <Geometry id=\"5\"/> --><Geometry id=\"1\"/><Geometry id=\"3\"/>\
             <MultiPatch><patches type=\"id_index\">3 1</patches></MultiPatch></xml>",
        )
        .unwrap();
        let ids: Vec<_> = patches(&doc)
            .unwrap()
            .iter()
            .map(|g| g.attribute("id").unwrap())
            .collect();
        assert_eq!(ids, ["3", "1"]);
        let doc = parse("<xml><Geometry id=\"0\"/><MultiPatch><patches type=\"id_range\">0 1</patches></MultiPatch></xml>").unwrap();
        let e = patches(&doc).unwrap_err();
        assert!(e.message.contains("id 1"), "{}", e.message);
    }

    #[test]
    fn syntax_errors_say_where() {
        let e = parse("<xml>\n<a></b></xml>").unwrap_err();
        assert!(e.message.contains("2:"), "{}", e.message);
    }
}

//! G+Smo XML read by a real XML parser: comments, CDATA and entities, several patches and the
//! `<MultiPatch>` references by id, for the B-rep reader and the THB-spline reader.

use crate::common;

use igaparam::boundary::{parse_gismo_xml, BoundaryLoop2, GismoGeometry};
use igaparam::spline::{read_gismo_thb, write_gismo_thb, SplineMap, ThbSpace};
use igaparam::tmesh::Tree;

fn puzzle() -> String {
    std::fs::read_to_string(common::boundary_data("puzzle3_bdry.xml")).unwrap()
}

/// The text of the first `<Geometry ...>...</Geometry>` element of `text`.
fn first_geometry(text: &str) -> &str {
    let start = text.find("<Geometry").unwrap();
    let end = text[start..].find("</Geometry>").unwrap() + start + "</Geometry>".len();
    &text[start..end]
}

#[test]
fn a_commented_out_geometry_is_not_read() {
    let text = puzzle();
    let expected = parse_gismo_xml(&text).unwrap();
    assert_eq!(expected.len(), 4);
    // A fifth curve, commented out, before the others; once with the file's <MultiPatch>, once
    // without it (every geometry of the file is then a patch).
    let commented = format!(
        "<!-- {} -->",
        first_geometry(&text).replace("id=\"0\"", "id=\"9\"")
    );
    let with_comment = text.replacen("<Geometry", &format!("{commented}\n <Geometry"), 1);
    assert_eq!(parse_gismo_xml(&with_comment).unwrap(), expected);
    let multipatch = with_comment.find("<MultiPatch").unwrap();
    let end = with_comment.find("</MultiPatch>").unwrap() + "</MultiPatch>".len();
    let without_multipatch = format!("{}{}", &with_comment[..multipatch], &with_comment[end..]);
    assert_eq!(parse_gismo_xml(&without_multipatch).unwrap(), expected);
    // The boundary loop of the file with the comment is the loop of the file.
    let dir = std::env::temp_dir().join(format!("igaparam-gismo-xml-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("puzzle_commented.xml");
    std::fs::write(&path, &with_comment).unwrap();
    let a = BoundaryLoop2::from_gismo_file(&path).unwrap();
    let b = BoundaryLoop2::from_gismo_file(common::boundary_data("puzzle3_bdry.xml")).unwrap();
    assert_eq!(a.corners(), b.corners());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn multipatch_references_pick_and_order_the_patches() {
    let text = puzzle();
    let curves = parse_gismo_xml(&text).unwrap();
    // A stray geometry that no patch names, and the patches listed by index in another order.
    let stray = first_geometry(&text).replace("id=\"0\"", "id=\"7\"");
    let edited = text
        .replacen("<Geometry", &format!("{stray}\n <Geometry"), 1)
        .replace(
            "<patches type=\"id_range\">0 3</patches>",
            "<patches type=\"id_index\">2 0 3 1</patches>",
        );
    let got = parse_gismo_xml(&edited).unwrap();
    assert_eq!(got, [2, 0, 3, 1].map(|i| curves[i].clone()));
    let missing = text.replace(">0 3</patches>", ">0 4</patches>");
    let e = parse_gismo_xml(&missing).unwrap_err();
    assert!(e.message.contains("id 4"), "{}", e.message);
}

#[test]
fn cdata_entities_and_syntax_errors() {
    let xml = "<?xml version=\"1.0\"?>\n<!DOCTYPE xml [<!ENTITY one \"1\">]>\n<xml>\n \
               <Geometry type=\"BSpline\" id=\"0\"><Basis type=\"BSplineBasis\">\
               <KnotVector degree=\"1\"><![CDATA[0 0]]> &one; &#49;</KnotVector></Basis>\
               <coefs geoDim=\"2\">0 0 <!-- 5 5 --> 2 1</coefs></Geometry>\n</xml>";
    let g = parse_gismo_xml(xml).unwrap();
    let GismoGeometry::Curve(c) = &g[0] else {
        panic!("expected a curve")
    };
    assert_eq!(c.eval(0.5), [1.0, 0.5, 0.0]);
    let e = parse_gismo_xml("<xml>\n<Geometry type=\"BSpline\">\n</xml>").unwrap_err();
    assert_eq!(e.kind, igaparam::ErrorKind::Io);
    assert!(e.message.contains("3:"), "{}", e.message);
}

/// A fitted 2D THB map over `tree`.
fn thb_map(tree: Tree<2>, scale: f64) -> SplineMap<2, ThbSpace<2>> {
    let space = ThbSpace::new(tree).unwrap();
    SplineMap::fit(space, |x: [f64; 2]| {
        Some([scale * (x[0] + 0.1 * x[1] * x[1]), x[1] + 0.2 * x[0]])
    })
    .unwrap()
    .0
}

/// A tree refined at the leaf holding `point`, twice.
fn refined_tree(point: [i64; 2]) -> Tree<2> {
    let mut tree = Tree::<2>::new();
    tree.refine_uniformly(1).unwrap();
    for _ in 0..2 {
        let leaf = tree.leaf_at(&point).unwrap();
        tree.refine(leaf).unwrap();
        tree.balance().unwrap();
    }
    tree
}

fn same_map(a: &SplineMap<2, ThbSpace<2>>, b: &SplineMap<2, ThbSpace<2>>) -> bool {
    a.element_count() == b.element_count() && a.control_points() == b.control_points()
}

#[test]
fn a_commented_out_box_is_not_applied() {
    let map = thb_map(refined_tree([1, 1]), 1.0);
    let text = write_gismo_thb(&map);
    let commented = text.replacen(
        "   <box",
        "   <!-- <box level=\"2\">4 4 8 8</box> -->\n   <box",
        1,
    );
    assert_ne!(commented, text);
    assert!(same_map(&read_gismo_thb::<2>(&commented).unwrap(), &map));
}

#[test]
fn two_thb_patches_keep_their_own_boxes() {
    let unit = igaparam::tmesh::UNIT as i64;
    let a = thb_map(refined_tree([1, 1]), 1.0);
    let b = thb_map(refined_tree([unit - 1, unit - 1]), 2.0);
    let body = |map: &SplineMap<2, ThbSpace<2>>, id: usize| {
        let text = write_gismo_thb(map);
        first_geometry(&text).replace("id=\"0\"", &format!("id=\"{id}\""))
    };
    let file = format!(
        "<?xml version=\"1.0\"?>\n<xml>\n{}\n{}\n<MultiPatch parDim=\"2\" id=\"2\">\
         <patches type=\"id_range\">0 1</patches></MultiPatch>\n</xml>\n",
        body(&a, 0),
        body(&b, 1)
    );
    assert!(same_map(&read_gismo_thb::<2>(&file).unwrap(), &a));
    let both = SplineMap::<2, ThbSpace<2>>::parse_gismo_patches(&file).unwrap();
    assert_eq!(both.len(), 2);
    assert!(same_map(&both[0], &a) && same_map(&both[1], &b));
    // Listed the other way round, patch 1 is the first.
    let swapped = file.replace("type=\"id_range\">0 1", "type=\"id_index\">1 0");
    assert!(same_map(&read_gismo_thb::<2>(&swapped).unwrap(), &b));
}

#[test]
fn thb_files_asking_for_absurd_refinement_are_refused() {
    let map = thb_map(refined_tree([1, 1]), 1.0);
    let text = write_gismo_thb(&map);
    // Both are refused from their counts, before anything is refined (which would take hours).
    // One box of level 20 over the whole square: 4^20 cells for a few dozen coefficients.
    let whole = text.replacen(
        "   <box",
        "   <box level=\"20\">0 0 1048576 1048576</box>\n   <box",
        1,
    );
    let e = read_gismo_thb::<2>(&whole).unwrap_err();
    assert!(e.message.contains("cells"), "{}", e.message);
    // Level-0 knots of 2^10 spans in each of three directions: 2^30 cells from 3 x 1031 knots.
    let knots: Vec<String> = (0..=1024)
        .map(|i| format!("{}", i as f64 / 1024.0))
        .collect();
    let kv = format!("0 0 0 {} 1 1 1", knots.join(" "));
    let bases: String = (0..3)
        .map(|i| format!("<Basis type=\"BSplineBasis\" index=\"{i}\"><KnotVector degree=\"3\">{kv}</KnotVector></Basis>"))
        .collect();
    let solid = format!(
        "<xml><Geometry type=\"THBSpline3\" id=\"0\"><Basis type=\"THBSplineBasis3\">\
         <Basis type=\"TensorBSplineBasis3\">{bases}</Basis></Basis>\
         <coefs geoDim=\"3\">0 0 0</coefs></Geometry></xml>"
    );
    let e = read_gismo_thb::<3>(&solid).unwrap_err();
    assert!(e.message.contains("1.074e9 cells"), "{}", e.message);
    // The map as written still reads back.
    assert!(same_map(&read_gismo_thb::<2>(&text).unwrap(), &map));
}

/// A file cut short (a transfer that stopped at 99% or halfway) is an I/O error, not a map or a
/// boundary made of what was read.
#[test]
fn a_file_cut_short_is_refused() {
    let thb = write_gismo_thb(&thb_map(refined_tree([1, 1]), 1.0));
    for text in [puzzle(), thb.clone()] {
        for fraction in [0.99, 0.5] {
            let mut cut = (text.len() as f64 * fraction) as usize;
            while !text.is_char_boundary(cut) {
                cut -= 1;
            }
            let cut = &text[..cut];
            let e = match parse_gismo_xml(cut) {
                Err(e) => e,
                Ok(g) => panic!("{fraction} of the file read as {} geometries", g.len()),
            };
            assert_eq!(e.kind, igaparam::ErrorKind::Io, "{}", e.message);
            assert!(
                read_gismo_thb::<2>(cut).is_err(),
                "{fraction} of the file read"
            );
        }
    }
    assert!(read_gismo_thb::<2>(&thb).is_ok());
}

/// `<box>` entries that are not boxes of knot spans of their level are refused with their line
/// (they used to be clamped or skipped in silence).
#[test]
fn malformed_boxes_are_refused() {
    let text = write_gismo_thb(&thb_map(refined_tree([1, 1]), 1.0));
    let start = text.find("<box").unwrap();
    let end = text[start..].find("</box>").unwrap() + start + "</box>".len();
    let first = &text[start..end];
    assert!(read_gismo_thb::<2>(&text).is_ok(), "{first}");
    for (bad, says) in [
        ("<box level=\"2\">0 0 1.5 2</box>", "not a knot-span index"),
        ("<box level=\"2\">0 0 5 2</box>", "not a knot-span index"),
        ("<box level=\"2\">-1 0 1 2</box>", "not a knot-span index"),
        ("<box level=\"2\">0 0 NaN 2</box>", "not a knot-span index"),
        ("<box level=\"2\">2 0 1 2</box>", "lower corner"),
        ("<box level=\"2\">0 1 1 1</box>", "lower corner"),
    ] {
        let e = read_gismo_thb::<2>(&text.replacen(first, bad, 1))
            .err()
            .unwrap_or_else(|| panic!("{bad} was read"));
        assert_eq!(e.kind, igaparam::ErrorKind::Io, "{bad}: {}", e.message);
        assert!(
            e.message.contains(says) && e.message.contains("line "),
            "{bad}: {}",
            e.message
        );
    }
}

/// Bases of a type the readers do not know are refused, not read as B-spline bases.
#[test]
fn unknown_basis_types_are_refused() {
    let thb = write_gismo_thb(&thb_map(refined_tree([1, 1]), 1.0));
    let other = thb.replacen(
        "<Basis type=\"BSplineBasis\" index=\"1\">",
        "<Basis type=\"LegendreBasis\" index=\"1\">",
        1,
    );
    assert_ne!(other, thb);
    let e = read_gismo_thb::<2>(&other).unwrap_err();
    assert!(e.message.contains("LegendreBasis"), "{}", e.message);
    let text = puzzle();
    let other = text.replacen(
        "<Basis type=\"BSplineBasis\">",
        "<Basis type=\"Bernstein\">",
        1,
    );
    assert_ne!(other, text);
    let e = parse_gismo_xml(&other).unwrap_err();
    assert_eq!(e.kind, igaparam::ErrorKind::Io);
    assert!(e.message.contains("Bernstein"), "{}", e.message);
}

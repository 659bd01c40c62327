//! Whether a planar T-mesh's image of the boundary is a simple closed curve.
//!
//! A boundary loop that does not cross itself can still be followed by a T-mesh whose boundary
//! facets cut across a thin neck or a tight bend: the polygon of their images then crosses
//! itself, and no placement of the inner vertices makes every cell valid. The check walks the
//! leaves' boundary facets around the unit square (counter-clockwise from (0, 0)), maps each
//! facet's first corner and midpoint by the boundary map, and looks for two non-neighbouring
//! edges of that polygon that cross or touch.
//!
//! A build or an update that ends with invalid cells on such a T-mesh fails with a message that
//! says where, instead of returning cells that cannot be made valid. (Refining the crossing
//! cells before the optimization was measured and not kept: on a U-shaped strip 0.2 wide it
//! left 8 of 22 cells invalid where the build's own repair leaves 1 of 49.)
//! Solids are not checked here: the images of their boundary faces are surfaces.

use super::build::Domain;
use super::cube_map::CubeMap;
use crate::boundary::crossing::TaggedPolygon;
use crate::boundary::Point2;
use crate::error::{Error, Result};
use crate::tmesh::{Tree, UNIT};

impl<const D: usize, B: CubeMap<D>> Domain<D, B> {
    /// Fails when `invalid_cells` cells are left invalid (any) on a T-mesh whose image of the
    /// boundary crosses itself, saying where; `Ok` otherwise, and always for solids.
    pub(super) fn refuse_crossing_image(&self, invalid_cells: usize) -> Result<()> {
        if invalid_cells == 0 {
            return Ok(());
        }
        let Some(crossing) = image_crossing(self.mesh.tree(), &self.framed_boundary()) else {
            return Ok(());
        };
        let at = self
            .frame
            .to_physical(std::array::from_fn(|k| crossing.at[k.min(1)]));
        let [p, q] = crossing.facets;
        Err(Error::invalid(format!(
            "{invalid_cells} cells stay invalid because the T-mesh's boundary facets cut across \
             the boundary: the images of the facets at ({}, {}) and ({}, {}) of the unit square \
             cross near ({}, {}); the boundary comes closer to itself there than the cells \
             resolve (lower the tolerance or raise min_level)",
            p[0], p[1], q[0], q[1], at[0], at[1]
        )))
    }
}

/// Two points, one on each of two boundary facets whose images cross or touch: the facets'
/// parametric midpoints on the boundary of the unit square, and the point the images share.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct ImageCrossing {
    /// The parametric midpoints of the two facets.
    pub facets: [[f64; 2]; 2],
    /// A point of both images (in the coordinates of the boundary map).
    pub at: Point2,
}

/// One leaf's facet on the boundary of the unit square: its place in the walk around the
/// square and its end points in the walk's direction (tree coordinates).
struct Facet {
    key: u64,
    start: [u64; 2],
    end: [u64; 2],
}

impl Facet {
    /// The facet's first corner and its midpoint, in unit-square coordinates.
    fn start_and_middle(&self) -> [[f64; 2]; 2] {
        let scale = 1.0 / UNIT as f64;
        let start = self.start.map(|v| v as f64 * scale);
        let middle = std::array::from_fn(|k| (self.start[k] + self.end[k]) as f64 * 0.5 * scale);
        [start, middle]
    }
}

/// The boundary facets of the leaves of a quadtree, in the order of a counter-clockwise walk
/// around the unit square starting at (0, 0); the first two coordinates of a tree of any
/// dimension are read.
fn boundary_facets<const D: usize>(tree: &Tree<D>) -> Vec<Facet> {
    let unit = UNIT as u64;
    let mut facets = Vec::new();
    for leaf in tree.leaves() {
        let cell = tree.cells()[leaf];
        let [i, j] = [0, 1].map(|k| u64::from(cell.lower[k]));
        let s = cell.side() as u64;
        let mut push = |key, start, end| facets.push(Facet { key, start, end });
        if j == 0 {
            push(i, [i, 0], [i + s, 0]);
        }
        if i + s == unit {
            push(unit + j, [unit, j], [unit, j + s]);
        }
        if j + s == unit {
            push(3 * unit - (i + s), [i + s, unit], [i, unit]);
        }
        if i == 0 {
            push(4 * unit - (j + s), [0, j + s], [0, j]);
        }
    }
    facets.sort_by_key(|f| f.key);
    facets
}

/// The first crossing (in the sweep order of [`first_crossing`]) of the polygon of the images of
/// the first corners and midpoints of a planar tree's boundary facets, or `None` when that
/// polygon is simple; always `None` for d ≠ 2.
pub(super) fn image_crossing<const D: usize>(
    tree: &Tree<D>,
    boundary: &impl CubeMap<D>,
) -> Option<ImageCrossing> {
    if D != 2 {
        return None;
    }
    let facets = boundary_facets(tree);
    let image = |p: [f64; 2]| -> Point2 {
        let x = boundary.boundary_point(std::array::from_fn(|k| p[k.min(1)]));
        [x[0], x[1]]
    };
    let mut polygon = TaggedPolygon::default();
    for (f, facet) in facets.iter().enumerate() {
        // A side mapped onto one point (a triangle's) gives repeated points: one is kept.
        for p in facet.start_and_middle().map(image) {
            polygon.push(p, f);
        }
    }
    let crossing = polygon.first_crossing()?;
    let middle = |edge: usize| facets[polygon.tag(edge)].start_and_middle()[1];
    Some(ImageCrossing {
        facets: [middle(crossing.first), middle(crossing.second)],
        at: crossing.at,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Identity;
    impl CubeMap<2> for Identity {
        fn boundary_point(&self, p: [f64; 2]) -> [f64; 2] {
            p
        }
    }

    /// The unit square whose top side dips below the bottom one halfway.
    struct Dipped;
    impl CubeMap<2> for Dipped {
        fn boundary_point(&self, p: [f64; 2]) -> [f64; 2] {
            match p[1] == 1.0 {
                true => [p[0], 1.0 - 1.5 * (std::f64::consts::PI * p[0]).sin()],
                false => p,
            }
        }
    }

    #[test]
    fn the_image_of_the_square_on_the_square_is_simple() {
        let mut tree = Tree::<2>::new();
        tree.refine_uniformly(3).unwrap();
        assert_eq!(image_crossing(&tree, &Identity), None);
        assert_eq!(boundary_facets(&tree).len(), 32);
        let keys: Vec<u64> = boundary_facets(&tree).iter().map(|f| f.key).collect();
        assert!(keys.windows(2).all(|w| w[0] < w[1]), "{keys:?}");
    }

    #[test]
    fn a_top_side_crossing_the_bottom_one_is_found() {
        let mut tree = Tree::<2>::new();
        tree.refine_uniformly(2).unwrap();
        let c = image_crossing(&tree, &Dipped).expect("the top crosses the bottom");
        assert!(c.facets.iter().any(|f| f[1] == 1.0), "{c:?}");
        assert!(c.facets.iter().any(|f| f[1] == 0.0), "{c:?}");
        assert!(c.at[1].abs() < 1e-12, "{c:?}");
        assert_eq!(image_crossing(&tree, &Identity), None);
    }
}

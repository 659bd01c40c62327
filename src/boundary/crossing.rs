//! Whether a closed polygon crosses itself: the check that a planar boundary loop is simple.
//!
//! Edges are swept in the order of their lowest x, each compared with the edges whose x-range
//! overlaps its own, so that the cost is near-linear for the boundaries met in practice
//! (coastlines of thousands of short edges) rather than quadratic.

use super::curve::Point2;

/// Two edges of a closed polygon that meet though they are not neighbours: edge `i` runs from
/// point `i` to point `i + 1` (the last one back to point 0), and `at` is a point they share.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Crossing {
    /// The edge of lower index.
    pub first: usize,
    /// The other edge.
    pub second: usize,
    /// A point of both edges.
    pub at: Point2,
}

/// The first pair (in sweep order) of edges of the closed polygon `points` that touch or cross
/// while not neighbours, or `None` when the polygon is simple. Consecutive equal points must
/// have been merged (an edge of zero length would make its neighbours look apart).
pub(crate) fn first_crossing(points: &[Point2]) -> Option<Crossing> {
    let n = points.len();
    if n < 4 {
        return None;
    }
    let edge = |i: usize| (points[i], points[(i + 1) % n]);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| low_x(edge(a)).total_cmp(&low_x(edge(b))));
    for (k, &i) in order.iter().enumerate() {
        let a = edge(i);
        let high = a.0[0].max(a.1[0]);
        for &j in &order[k + 1..] {
            let b = edge(j);
            if low_x(b) > high {
                break;
            }
            let gap = i.abs_diff(j);
            if gap <= 1 || gap == n - 1 {
                continue;
            }
            if let Some(at) = meet(a, b) {
                return Some(Crossing {
                    first: i.min(j),
                    second: i.max(j),
                    at,
                });
            }
        }
    }
    None
}

/// A closed polygon built point by point, each point tagged with what it was taken from (a
/// curve, a facet), consecutive repeats merged as [`first_crossing`] needs.
#[derive(Default)]
pub(crate) struct TaggedPolygon {
    points: Vec<Point2>,
    tags: Vec<usize>,
}

impl TaggedPolygon {
    /// Appends `p`, unless it repeats the last point.
    pub(crate) fn push(&mut self, p: Point2, tag: usize) {
        if self.points.last() != Some(&p) {
            self.points.push(p);
            self.tags.push(tag);
        }
    }

    /// Closes the polygon (drops last points that repeat the first) and returns its first
    /// crossing, as [`first_crossing`].
    pub(crate) fn first_crossing(&mut self) -> Option<Crossing> {
        while self.points.len() > 1 && self.points.last() == self.points.first() {
            self.points.pop();
            self.tags.pop();
        }
        first_crossing(&self.points)
    }

    /// The tag of edge `edge` (that of its first point).
    pub(crate) fn tag(&self, edge: usize) -> usize {
        self.tags[edge]
    }

    /// The number of points.
    pub(crate) fn point_count(&self) -> usize {
        self.points.len()
    }
}

fn low_x((p, q): (Point2, Point2)) -> f64 {
    p[0].min(q[0])
}

/// Twice the signed area of the triangle `a b c`.
fn orient(a: Point2, b: Point2, c: Point2) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether `c`, collinear with segment `ab`, lies within its bounding box.
fn within(a: Point2, b: Point2, c: Point2) -> bool {
    let inside = |k: usize| a[k].min(b[k]) <= c[k] && c[k] <= a[k].max(b[k]);
    inside(0) && inside(1)
}

/// A point shared by the segments `a` and `b` (crossing, touching or overlapping), if any.
fn meet(a: (Point2, Point2), b: (Point2, Point2)) -> Option<Point2> {
    let (p, q) = a;
    let (r, s) = b;
    let (d1, d2) = (orient(r, s, p), orient(r, s, q));
    let (d3, d4) = (orient(p, q, r), orient(p, q, s));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        let t = d1 / (d1 - d2);
        return Some([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
    }
    // Touching: an end point of one segment on the other.
    [(d1, r, s, p), (d2, r, s, q), (d3, p, q, r), (d4, p, q, s)]
        .into_iter()
        .find(|&(d, u, v, c)| d == 0.0 && within(u, v, c))
        .map(|(_, _, _, c)| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_is_simple() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(first_crossing(&square), None);
    }

    #[test]
    fn a_bow_tie_crosses_at_its_middle() {
        let bow = [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]];
        let c = first_crossing(&bow).expect("a crossing");
        assert_eq!((c.first, c.second), (0, 2));
        assert!((c.at[0] - 0.5).abs() < 1e-15 && (c.at[1] - 0.5).abs() < 1e-15);
    }

    #[test]
    fn a_loop_touching_itself_is_not_simple() {
        // The vertex (1, 0) lies on the edge from (0, 0) to (2, 0): two triangles joined at a
        // point.
        let pinched = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [1.0, 0.0], [0.0, 2.0]];
        let c = first_crossing(&pinched).expect("a touch");
        assert_eq!(c.at, [1.0, 0.0]);
    }

    #[test]
    fn a_fine_circle_is_simple_and_a_figure_eight_is_not() {
        let n = 2000;
        let circle: Vec<Point2> = (0..n)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / n as f64;
                [t.cos(), t.sin()]
            })
            .collect();
        assert_eq!(first_crossing(&circle), None);
        let eight: Vec<Point2> = (0..n)
            .map(|i| {
                let t = std::f64::consts::TAU * (i as f64 + 0.5) / n as f64;
                [t.sin(), (2.0 * t).sin() / 2.0]
            })
            .collect();
        let c = first_crossing(&eight).expect("the figure eight crosses at the origin");
        assert!(c.at[0].abs() < 1e-3 && c.at[1].abs() < 1e-3, "{:?}", c.at);
    }
}

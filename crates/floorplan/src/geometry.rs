//! Axis-aligned geometry on the floor plane: rectangles, rectilinear polygons and segments.

use nalgebra::Point2;

/// Distances below this (m) count as equal.
pub const EPS: f64 = 1e-6;

/// An axis-aligned rectangle in (x, z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// Corner with the smallest x and z.
    pub min: Point2<f64>,
    /// Corner with the largest x and z.
    pub max: Point2<f64>,
}

impl Rect {
    /// The rectangle between two corners given as `(x0, z0, x1, z1)`.
    pub fn new(x0: f64, z0: f64, x1: f64, z1: f64) -> Self {
        Self {
            min: Point2::new(x0.min(x1), z0.min(z1)),
            max: Point2::new(x0.max(x1), z0.max(z1)),
        }
    }

    /// Width along x.
    pub fn width(&self) -> f64 {
        self.max.x - self.min.x
    }

    /// Depth along z.
    pub fn depth(&self) -> f64 {
        self.max.y - self.min.y
    }

    /// Area in m².
    pub fn area(&self) -> f64 {
        self.width() * self.depth()
    }

    /// Area of the overlap with another rectangle (0 when they only touch).
    pub fn overlap_area(&self, other: &Rect) -> f64 {
        let w = self.max.x.min(other.max.x) - self.min.x.max(other.min.x);
        let d = self.max.y.min(other.max.y) - self.min.y.max(other.min.y);
        w.max(0.0) * d.max(0.0)
    }

    /// The four corners, counter-clockwise seen from +y with x right and z down the page
    /// (min corner first).
    pub fn polygon(&self) -> Vec<Point2<f64>> {
        vec![
            self.min,
            Point2::new(self.max.x, self.min.y),
            self.max,
            Point2::new(self.min.x, self.max.y),
        ]
    }
}

/// Which axis a segment runs along.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Axis {
    /// Along x (constant z).
    X,
    /// Along z (constant x).
    Z,
}

/// An axis-aligned segment: `axis`, the constant coordinate `at`, and the interval `lo..hi`
/// along the axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// The axis it runs along.
    pub axis: Axis,
    /// The coordinate across the axis (z for [`Axis::X`], x for [`Axis::Z`]).
    pub at: f64,
    /// Start along the axis.
    pub lo: f64,
    /// End along the axis (`lo < hi`).
    pub hi: f64,
}

impl Segment {
    /// Length in m.
    pub fn length(&self) -> f64 {
        self.hi - self.lo
    }

    /// The point at `t` along the axis.
    pub fn point(&self, t: f64) -> Point2<f64> {
        match self.axis {
            Axis::X => Point2::new(t, self.at),
            Axis::Z => Point2::new(self.at, t),
        }
    }

    /// The start and end points.
    pub fn ends(&self) -> (Point2<f64>, Point2<f64>) {
        (self.point(self.lo), self.point(self.hi))
    }

    /// Where a point lies along the axis, if it is on the segment's line.
    pub fn along(&self, p: &Point2<f64>) -> Option<f64> {
        let (across, along) = match self.axis {
            Axis::X => (p.y, p.x),
            Axis::Z => (p.x, p.y),
        };
        ((across - self.at).abs() < 1e-3).then_some(along)
    }

    /// Whether the interval `centre ± half` lies on the segment.
    pub fn holds(&self, centre: &Point2<f64>, half: f64) -> bool {
        self.along(centre)
            .is_some_and(|t| t - half >= self.lo - 1e-3 && t + half <= self.hi + 1e-3)
    }

    /// The unit vector along the axis, in (x, z).
    pub fn direction(&self) -> nalgebra::Vector2<f64> {
        match self.axis {
            Axis::X => nalgebra::Vector2::new(1.0, 0.0),
            Axis::Z => nalgebra::Vector2::new(0.0, 1.0),
        }
    }
}

/// Why a polygon is not a supported room outline.
pub fn polygon_problem(polygon: &[Point2<f64>]) -> Option<String> {
    if polygon.len() < 4 {
        return Some(format!("has {} corners (at least 4)", polygon.len()));
    }
    if polygon.iter().any(|p| !p.x.is_finite() || !p.y.is_finite()) {
        return Some("has a corner that is not a finite number".into());
    }
    let edges = edges(polygon);
    for (i, (a, b)) in edges.iter().enumerate() {
        let (dx, dz) = ((b.x - a.x).abs(), (b.y - a.y).abs());
        if dx < EPS && dz < EPS {
            return Some(format!("edge {i} has zero length"));
        }
        if dx > EPS && dz > EPS {
            return Some(format!("edge {i} is not parallel to x or z"));
        }
    }
    for i in 0..edges.len() {
        let next = (i + 1) % edges.len();
        if axis_of(edges[i]) == axis_of(edges[next]) {
            return Some(format!(
                "edges {i} and {next} run the same way (drop the corner between them)"
            ));
        }
    }
    crossing(&edges).map(|(i, j)| format!("edges {i} and {j} cross or touch"))
}

fn edges(polygon: &[Point2<f64>]) -> Vec<(Point2<f64>, Point2<f64>)> {
    (0..polygon.len())
        .map(|i| (polygon[i], polygon[(i + 1) % polygon.len()]))
        .collect()
}

fn axis_of((a, b): (Point2<f64>, Point2<f64>)) -> Axis {
    if (b.x - a.x).abs() > (b.y - a.y).abs() {
        Axis::X
    } else {
        Axis::Z
    }
}

/// The first pair of non-neighbouring edges that meet.
fn crossing(edges: &[(Point2<f64>, Point2<f64>)]) -> Option<(usize, usize)> {
    let n = edges.len();
    for i in 0..n {
        for j in i + 1..n {
            let neighbours = j == i + 1 || (i == 0 && j == n - 1);
            if !neighbours && boxes_meet(edges[i], edges[j]) {
                return Some((i, j));
            }
        }
    }
    None
}

fn boxes_meet(a: (Point2<f64>, Point2<f64>), b: (Point2<f64>, Point2<f64>)) -> bool {
    let lo = |p: Point2<f64>, q: Point2<f64>| (p.x.min(q.x), p.y.min(q.y));
    let hi = |p: Point2<f64>, q: Point2<f64>| (p.x.max(q.x), p.y.max(q.y));
    let (alo, ahi, blo, bhi) = (lo(a.0, a.1), hi(a.0, a.1), lo(b.0, b.1), hi(b.0, b.1));
    alo.0 <= bhi.0 + EPS && blo.0 <= ahi.0 + EPS && alo.1 <= bhi.1 + EPS && blo.1 <= ahi.1 + EPS
}

/// Whether a point lies strictly inside a simple rectilinear polygon (ray casting along +x).
pub fn contains(polygon: &[Point2<f64>], p: Point2<f64>) -> bool {
    let mut inside = false;
    for (a, b) in edges(polygon) {
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if p.x < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// A simple rectilinear polygon cut into rectangles along its corners' x coordinates.
pub fn rectangles(polygon: &[Point2<f64>]) -> Vec<Rect> {
    let xs = sorted_unique(polygon.iter().map(|p| p.x));
    let zs = sorted_unique(polygon.iter().map(|p| p.y));
    let mut out = Vec::new();
    for xw in xs.windows(2) {
        for zw in zs.windows(2) {
            let mid = Point2::new((xw[0] + xw[1]) / 2.0, (zw[0] + zw[1]) / 2.0);
            if contains(polygon, mid) {
                out.push(Rect::new(xw[0], zw[0], xw[1], zw[1]));
            }
        }
    }
    out
}

/// Floor area of a simple polygon (shoelace), m².
pub fn area(polygon: &[Point2<f64>]) -> f64 {
    let twice: f64 = edges(polygon)
        .iter()
        .map(|(a, b)| a.x * b.y - b.x * a.y)
        .sum();
    twice.abs() / 2.0
}

/// The polygon's edges as segments, each with the side its interior lies on: `+1.0` when the
/// interior is at larger `at`, `-1.0` when at smaller.
pub fn sided_edges(polygon: &[Point2<f64>]) -> Vec<(Segment, f64)> {
    edges(polygon)
        .into_iter()
        .map(|(a, b)| {
            let seg = match axis_of((a, b)) {
                Axis::X => Segment {
                    axis: Axis::X,
                    at: a.y,
                    lo: a.x.min(b.x),
                    hi: a.x.max(b.x),
                },
                Axis::Z => Segment {
                    axis: Axis::Z,
                    at: a.x,
                    lo: a.y.min(b.y),
                    hi: a.y.max(b.y),
                },
            };
            let mid = seg.point((seg.lo + seg.hi) / 2.0);
            let probe = match seg.axis {
                Axis::X => Point2::new(mid.x, mid.y + 1e-4),
                Axis::Z => Point2::new(mid.x + 1e-4, mid.y),
            };
            let side = if contains(polygon, probe) { 1.0 } else { -1.0 };
            (seg, side)
        })
        .collect()
}

/// The outline of a union of rectangles that forms one simple polygon (rectangle, L, T or U),
/// corners in order with collinear corners dropped; `None` when the union is empty, falls apart
/// or touches itself at a corner.
pub fn union_outline(rects: &[Rect]) -> Option<Vec<Point2<f64>>> {
    let xs = sorted_unique(rects.iter().flat_map(|r| [r.min.x, r.max.x]));
    let zs = sorted_unique(rects.iter().flat_map(|r| [r.min.y, r.max.y]));
    let inside = |i: isize, j: isize| {
        if i < 0 || j < 0 || i as usize + 1 >= xs.len() || j as usize + 1 >= zs.len() {
            return false;
        }
        let (i, j) = (i as usize, j as usize);
        let mid = Point2::new((xs[i] + xs[i + 1]) / 2.0, (zs[j] + zs[j + 1]) / 2.0);
        rects
            .iter()
            .any(|r| r.min.x < mid.x && mid.x < r.max.x && r.min.y < mid.y && mid.y < r.max.y)
    };
    let mut next: std::collections::BTreeMap<(isize, isize), (isize, isize)> = Default::default();
    for i in 0..xs.len().saturating_sub(1) as isize {
        for j in 0..zs.len().saturating_sub(1) as isize {
            if !inside(i, j) {
                continue;
            }
            let sides = [
                ((i, j), (i + 1, j), (i, j - 1)),
                ((i + 1, j), (i + 1, j + 1), (i + 1, j)),
                ((i + 1, j + 1), (i, j + 1), (i, j + 1)),
                ((i, j + 1), (i, j), (i - 1, j)),
            ];
            for (from, to, beyond) in sides {
                if !inside(beyond.0, beyond.1) && next.insert(from, to).is_some() {
                    return None;
                }
            }
        }
    }
    let start = *next.keys().next()?;
    let mut corners = vec![start];
    let mut at = next[&start];
    while at != start {
        corners.push(at);
        at = *next.get(&at)?;
        if corners.len() > next.len() {
            return None;
        }
    }
    if corners.len() != next.len() {
        return None;
    }
    let n = corners.len();
    let keep = |k: usize| {
        let (a, b, c) = (corners[(k + n - 1) % n], corners[k], corners[(k + 1) % n]);
        !((a.0 == b.0 && b.0 == c.0) || (a.1 == b.1 && b.1 == c.1))
    };
    let outline = (0..n)
        .filter(|&k| keep(k))
        .map(|k| Point2::new(xs[corners[k].0 as usize], zs[corners[k].1 as usize]))
        .collect();
    Some(outline)
}

fn sorted_unique(values: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut v: Vec<f64> = values.collect();
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() < EPS);
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(v: &[(f64, f64)]) -> Vec<Point2<f64>> {
        v.iter().map(|&(x, z)| Point2::new(x, z)).collect()
    }

    #[test]
    fn l_shape_cuts_into_rectangles_of_its_area() {
        let l = pts(&[
            (0.0, 0.0),
            (4.0, 0.0),
            (4.0, 2.0),
            (2.0, 2.0),
            (2.0, 4.0),
            (0.0, 4.0),
        ]);
        assert_eq!(polygon_problem(&l), None);
        let rects = rectangles(&l);
        let sum: f64 = rects.iter().map(Rect::area).sum();
        assert!((sum - 12.0).abs() < 1e-9 && (area(&l) - 12.0).abs() < 1e-9);
        assert!(contains(&l, Point2::new(1.0, 3.0)) && !contains(&l, Point2::new(3.0, 3.0)));
    }

    #[test]
    fn unions_trace_to_l_and_u_outlines() {
        let l =
            union_outline(&[Rect::new(0.0, 0.0, 2.0, 4.0), Rect::new(2.0, 2.0, 5.0, 4.0)]).unwrap();
        assert_eq!(l.len(), 6, "{l:?}");
        assert!((area(&l) - 14.0).abs() < 1e-9 && polygon_problem(&l).is_none());
        let u = union_outline(&[
            Rect::new(0.0, 0.0, 1.0, 3.0),
            Rect::new(1.0, 2.0, 3.0, 3.0),
            Rect::new(3.0, 0.0, 4.0, 3.0),
        ])
        .unwrap();
        assert_eq!(u.len(), 8);
        assert!(
            union_outline(&[Rect::new(0.0, 0.0, 1.0, 1.0), Rect::new(2.0, 0.0, 3.0, 1.0)])
                .is_none()
        );
        let rect =
            union_outline(&[Rect::new(0.0, 0.0, 1.0, 1.0), Rect::new(1.0, 0.0, 3.0, 1.0)]).unwrap();
        assert_eq!(rect.len(), 4);
    }

    #[test]
    fn bad_outlines_say_why() {
        let slanted = pts(&[(0.0, 0.0), (4.0, 1.0), (4.0, 3.0), (0.0, 3.0)]);
        assert!(polygon_problem(&slanted).unwrap().contains("not parallel"));
        let bowtie = pts(&[
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 2.0),
            (4.0, 2.0),
            (4.0, 4.0),
            (3.0, 4.0),
            (3.0, -1.0),
            (0.0, -1.0),
        ]);
        assert!(polygon_problem(&bowtie).is_some());
        assert!(polygon_problem(&pts(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)])).is_some());
    }

    #[test]
    fn edges_know_their_inside() {
        let r = Rect::new(0.0, 0.0, 3.0, 2.0).polygon();
        for (seg, side) in sided_edges(&r) {
            let mid = seg.point((seg.lo + seg.hi) / 2.0);
            let probe = match seg.axis {
                Axis::X => Point2::new(mid.x, mid.y + side * 0.1),
                Axis::Z => Point2::new(mid.x + side * 0.1, mid.y),
            };
            assert!(contains(&r, probe), "{seg:?}");
        }
    }
}

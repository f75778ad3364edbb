//! The square around the light cut by a triangle's half-planes, and the
//! lines and crossings it is cut with.

use super::image::Image;
use crate::kernel::receiver_view::union::Measure;
use glam::DVec2;
use std::f64::consts::SQRT_2;

/// The largest error, in half-widths of the square, of a vertex computed
/// from its two lines alone (beyond it, as where two lines are nearly
/// parallel, the vertex is the crossing on the edge being cut).
pub(super) const WELL_PLACED: f64 = 1.0 / (1u64 << 30) as f64;

/// A half-plane `a X + b Y + c ≥ 0` of the light's plane (view
/// coordinates), and bounds on how far its line may lie from the exact
/// one over the square: `err` from the cheap bounds, which takes every
/// decision (so that the image is the same with or without the certified
/// bound), and `tight`, at most `err`, the closer one the bound reports.
#[derive(Clone, Copy, Debug)]
pub(super) struct Line {
    pub(super) a: f64,
    pub(super) b: f64,
    pub(super) c: f64,
    pub(super) err: f64,
    pub(super) tight: f64,
}

impl Line {
    fn at(&self, q: DVec2) -> f64 {
        self.a * q.x + self.b * q.y + self.c
    }

    /// The larger coefficient: distances in the view are values over it.
    pub(super) fn norm(&self) -> f64 {
        self.a.abs().max(self.b.abs())
    }

    /// A bound on the rounding of [`Line::at`]: `4u` of its terms'
    /// magnitudes.
    fn rounding(&self, q: DVec2) -> f64 {
        let terms = (self.a * q.x).abs() + (self.b * q.y).abs() + self.c.abs();
        4.0 * f64::EPSILON * terms
    }
}

/// The line a clipped image's edge lies on: a side of the square (bottom,
/// right, top, left), the plane through `p` and the edge opposite a corner,
/// or the triangle's own plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum On {
    Side(u8),
    Cone(u8),
    Plane,
}

/// The square cut by half-planes, each vertex computed from the two lines
/// it lies on — a line and a side of the square from the line's
/// coefficients, two planes through `p` at their common corner's image —
/// never from the segment being cut, so that two triangles sharing an edge
/// (the same line, bit for bit) and a corner get the same vertices: their
/// shared edges are exactly reverse and drop out of the union. Each vertex
/// carries a bound on its error.
pub(super) struct Clip {
    image: Image,
    /// The line of the edge from each vertex to the next.
    on: [On; Image::CAP],
    /// The lines cut by so far (cone planes 0–2, the plane 3).
    lines: [Option<Line>; 4],
    half: f64,
    /// The light in the view's coordinates: a disk of this radius, or
    /// (`None`) the square `[−1, 1]²`.
    disk: Option<f64>,
    /// The allowance of a thin image within its lines' errors of being
    /// cut away whole (see [`Image::extra`]).
    extra: f64,
}

impl Clip {
    pub(super) fn new(h: f64, measure: Measure) -> Clip {
        let z = DVec2::ZERO;
        let image = Image {
            v: [
                DVec2::new(-h, -h),
                DVec2::new(h, -h),
                DVec2::new(h, h),
                DVec2::new(-h, h),
                z,
                z,
                z,
                z,
            ],
            len: 4,
            ..Image::EMPTY
        };
        let mut on = [On::Plane; Image::CAP];
        on[..4].copy_from_slice(&[On::Side(0), On::Side(1), On::Side(2), On::Side(3)]);
        Clip {
            image,
            on,
            lines: [None; 4],
            half: h,
            disk: match measure {
                Measure::Disk(r) => Some(r),
                Measure::Square => None,
            },
            extra: 0.0,
        }
    }

    /// Cuts by the half-plane `s · line ≥ 0` (`s = ±1`), or by a line that
    /// misses the square (`Err(inside)`: keep all or none); whether
    /// anything is left. `corner(k)` is the image of the triangle's corner
    /// `k` (where two cone planes meet), if it lies in front of `p`.
    /// Sutherland–Hodgman: nothing is left when no vertex is strictly
    /// inside (the rest has no area: a triangle lying in the light's own
    /// plane hides nothing, as the open segment says).
    pub(super) fn cut(
        &mut self,
        id: On,
        line: Result<Line, bool>,
        s: f64,
        mut corner: impl FnMut(usize) -> Option<(DVec2, f64)>,
    ) -> bool {
        let line = match line {
            Ok(l) => Line {
                a: s * l.a,
                b: s * l.b,
                c: s * l.c,
                err: l.err,
                tight: l.tight,
            },
            Err(inside) => {
                if (s > 0.0) != inside {
                    self.image.len = 0;
                }
                return self.image.len > 0;
            }
        };
        let slot = match id {
            On::Cone(i) => usize::from(i),
            _ => 3,
        };
        self.lines[slot] = Some(line);
        let n = self.image.len;
        let mut f = [0.0; Image::CAP];
        let (mut any_in, mut all_in) = (false, true);
        for (fk, &v) in f.iter_mut().zip(&self.image.v[..n]) {
            *fk = line.at(v);
            any_in |= *fk > 0.0;
            all_in &= *fk >= 0.0;
        }
        if !any_in {
            // The exact image may still be a sliver within the lines'
            // errors of the vertices left.
            let norm = line.norm();
            let (most, err) = (0..n).fold((f64::NEG_INFINITY, 0.0_f64), |(m, e), k| {
                (m.max(f[k] / norm), e.max(self.image.err[k]))
            });
            if most > -(line.tight + err) * 2.0 {
                let band = self.band(&self.image.v[..n], &line, 1.0, line.tight, err);
                self.extra += band.min(self.wedge(slot, &line, 1.0, 0.0));
            }
            self.image.len = 0;
            return false;
        }
        if all_in {
            return true;
        }
        // The new polygon, into local arrays (copied back at the end).
        let mut v = [DVec2::ZERO; Image::CAP];
        let mut errs = [0.0; Image::CAP];
        let mut on = [On::Plane; Image::CAP];
        let mut len = 0;
        let mut push = |q: DVec2, err: f64, id: On| {
            if len < Image::CAP {
                (v[len], errs[len], on[len]) = (q, err, id);
                len += 1;
            }
        };
        for k in 0..n {
            // The next vertex, without a division.
            let j = if k + 1 == n { 0 } else { k + 1 };
            let (fa, fb) = (f[k], f[j]);
            if fa >= 0.0 {
                // A vertex on the line whose next one is outside: the
                // boundary leaves it along the new line (its old edge runs
                // out of the half-plane), and no crossing follows.
                let next = if fa == 0.0 && fb < 0.0 {
                    id
                } else {
                    self.on[k]
                };
                push(self.image.v[k], self.image.err[k], next);
            }
            if (fa > 0.0 && fb < 0.0) || (fa < 0.0 && fb > 0.0) {
                let (a, b) = (self.image.v[k], self.image.v[j]);
                let (mut q, mut err) = self.meet(id, self.on[k], &mut corner);
                // Where the two lines are so nearly parallel (or the
                // corner so ill-placed) that their meeting point falls off
                // the edge being cut, or out of the square (the union
                // takes every image to lie in it), the crossing on the
                // edge: within its ends' and the line's errors over the
                // sine of the angle, and the edge's length.
                let (lo, hi) = (a.min(b), a.max(b));
                let slack = WELL_PLACED * self.half;
                let on_edge = q.cmpge(lo - slack).all() && q.cmple(hi + slack).all();
                let h = DVec2::splat(self.half);
                let in_square = q.cmpge(-h).all() && q.cmple(h).all();
                if !(err <= slack && on_edge && in_square) {
                    q = crossing(a, fa, b, fb);
                    err = err.min(
                        (b - a).abs().max_element() + self.image.err[k].max(self.image.err[j]),
                    );
                }
                // Leaving: the boundary follows the new line; entering: the
                // rest of the edge.
                push(q, err, if fa > 0.0 { id } else { self.on[k] });
            }
        }
        self.image.v[..len].copy_from_slice(&v[..len]);
        self.image.err[..len].copy_from_slice(&errs[..len]);
        self.on[..len].copy_from_slice(&on[..len]);
        self.image.len = len;
        len >= 3
    }

    /// The image with each vertex's distance from its edges' computed
    /// lines (a posteriori, in place of the construction's errors), and
    /// each edge's area allowance: an edge on a line whose error is `δ`
    /// (a side of the square: 0), its ends within `ρ` of their lines, lies
    /// within `δ + ρ` of the exact image's edge on that line, which may run
    /// on past either end by `(δ_in + δ_out + 2ρ) / sin θ` (`θ` the angle of
    /// the two lines there, at most the square's diagonal): a band of twice
    /// `δ + ρ` along that length holds what the two images differ by near
    /// the edge. A line passing within its error of a vertex without
    /// cutting the image adds a band along the square's diagonal
    /// ([`Image::extra`]).
    pub(super) fn finish<const B: bool>(mut self) -> Image {
        let n = self.image.len;
        let mut image = self.image;
        image.extra = self.extra;
        if n < 3 {
            image.len = 0;
            return image;
        }
        if !B {
            return image;
        }
        let diagonal = 2.0 * SQRT_2 * self.half;
        let line = |id: On| match id {
            On::Cone(i) => self.lines[usize::from(i)],
            On::Plane => self.lines[3],
            On::Side(_) => None,
        };
        // Per edge: its line, the line's error and normal.
        let mut lines = [None; Image::CAP];
        let mut delta = [0.0; Image::CAP];
        let mut normal = [DVec2::ZERO; Image::CAP];
        for k in 0..n {
            let id = self.on[k];
            lines[k] = line(id);
            (delta[k], normal[k]) = match (id, lines[k]) {
                (On::Side(0 | 2), _) => (0.0, DVec2::Y),
                (On::Side(_), _) => (0.0, DVec2::X),
                (_, Some(l)) => (l.tight, DVec2::new(l.a, l.b)),
                (_, None) => (0.0, DVec2::ZERO),
            };
        }
        let dist = |q: DVec2, k: usize| distance_from(self.on[k], &lines[k], q, self.half);
        let prev = |k: usize| if k == 0 { n - 1 } else { k - 1 };
        let mut rho = [0.0; Image::CAP];
        for (k, (r, &q)) in rho.iter_mut().zip(&image.v[..n]).enumerate() {
            *r = dist(q, prev(k)).max(dist(q, k));
        }
        let mut ext = [0.0; Image::CAP];
        for k in 0..n {
            let (a, b) = (prev(k), k);
            let (na, nb) = (normal[a], normal[b]);
            let sin = na.perp_dot(nb).abs() / (na.length() * nb.length());
            let e = (delta[a] + delta[b] + 2.0 * rho[k]) / sin;
            ext[k] = if e < diagonal { e } else { diagonal };
        }
        for k in 0..n {
            let j = if k + 1 == n { 0 } else { k + 1 };
            image.err[k] = rho[k];
            image.w[k] = match self.on[k] {
                On::Side(_) => 0.0,
                _ => {
                    let width = delta[k] + rho[k].max(rho[j]);
                    let length = (image.v[j] - image.v[k]).length() + ext[k] + ext[j];
                    2.0 * width
                        * length.min(diagonal + ext[k] + ext[j])
                        * (1.0 + 8.0 * f64::EPSILON)
                }
            };
        }
        let most_rho = rho[..n].iter().fold(0.0_f64, |m, &r| m.max(r));
        // The reach (see [`Image::reach`]): the bands' widths and runs
        // past their ends, and for each line cut by, its error plus how
        // far any vertex lies on its outer side (`τ`): a point more than
        // `δ + τ` inside every edge line of a triangle of this image is
        // more than `δ` inside this line (the triangle lies where the line
        // is at least `−τ`, and its value grows at least as fast as the
        // distance), so inside the exact line too.
        let (mut reach, mut spread) = (0.0_f64, 0.0_f64);
        for k in 0..n {
            if !matches!(self.on[k], On::Side(_)) {
                let j = if k + 1 == n { 0 } else { k + 1 };
                let width = delta[k] + rho[k].max(rho[j]);
                reach = reach.max(width).max(ext[k]).max(ext[j]);
                spread = spread.max(width.hypot(ext[k].max(ext[j])));
            }
        }
        for (slot, l) in self.lines.iter().enumerate() {
            let Some(l) = l else { continue };
            let near = image.v[..n]
                .iter()
                .map(|&q| (l.at(q) - l.rounding(q)) / l.norm())
                .fold(f64::INFINITY, f64::min);
            reach = reach.max(l.tight + (-near).max(0.0));
            let id = if slot == 3 {
                On::Plane
            } else {
                On::Cone(slot as u8)
            };
            if self.on[..n].contains(&id) {
                continue;
            }
            if near < (l.tight + most_rho) * 2.0 {
                let band = self.band(&image.v[..n], l, -1.0, l.tight, most_rho);
                image.extra += band.min(self.wedge(slot, l, -1.0, most_rho));
            }
        }
        // A NaN (a line's value at a vertex not finite) reaches anywhere.
        image.reach = if reach.is_finite() {
            reach * (1.0 + 8.0 * f64::EPSILON)
        } else {
            f64::INFINITY
        };
        image.spread = if spread.is_finite() {
            spread * (1.0 + 8.0 * f64::EPSILON)
        } else {
            f64::INFINITY
        };
        self.image = image;
        self.image
    }

    /// The area the exact image may differ by near a line that the
    /// convex polygon `v` (vertices within `e` of the exact ones) lies
    /// within `2(δ + e)` of without being cut by it (`σ = 1`: `v` on the
    /// line's negative side, the image may be a sliver across it; `σ = −1`:
    /// `v` on its positive side, the exact line may cut a sliver off), the
    /// line within `δ` of the exact one over the square: a band of width
    /// `2(δ + e)` along the part `Q` of `v` where `σ · line ≥ −2(δ + e)`
    /// (in units of its larger coefficient), that part grown by `e`;
    /// nothing where `Q` so grown misses the light. `Q` lies in the box of
    /// the vertices in that slab and the edges' crossings of its side,
    /// each crossing within the rounding of its parameter (the lines'
    /// values are within [`Line::rounding`] of the exact ones).
    fn band(&self, v: &[DVec2], line: &Line, sigma: f64, delta: f64, e: f64) -> f64 {
        const U4: f64 = 4.0 * f64::EPSILON;
        let level = -2.0 * (delta + e);
        let norm = line.norm();
        let value = |q: DVec2| (sigma * line.at(q) / norm, line.rounding(q) / norm);
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        let mut margin = 0.0_f64;
        let n = v.len();
        for k in 0..n {
            let j = if k + 1 == n { 0 } else { k + 1 };
            let ((ga, ea), (gb, eb)) = (value(v[k]), value(v[j]));
            let (a_in, b_in) = (ga >= level - ea, gb >= level - eb);
            if a_in {
                (lo, hi) = (lo.min(v[k]), hi.max(v[k]));
            }
            if a_in != b_in {
                // The crossing of the slab's side (its parameter within the
                // values' errors over their difference, and its rounding).
                let q = crossing(v[k], ga - level, v[j], gb - level);
                let dt = (ea + eb) / (ga - gb).abs() + U4;
                (lo, hi) = (lo.min(q), hi.max(q));
                margin = margin.max((v[j] - v[k]).length() * dt + U4 * q.abs().max_element());
            }
        }
        let diagonal = 2.0 * SQRT_2 * self.half;
        let width = 2.0 * (delta + e);
        let grow = DVec2::splat(e + margin);
        let (lo, hi) = (lo - grow, hi + grow);
        if !(lo.x <= hi.x && lo.y <= hi.y && margin.is_finite()) {
            // No box (values not finite): the band along the whole square.
            return width * diagonal;
        }
        let misses = match self.disk {
            Some(r) => DVec2::ZERO.clamp(lo, hi).length() > r * (1.0 + U4),
            None => lo.x > 1.0 || lo.y > 1.0 || hi.x < -1.0 || hi.y < -1.0,
        };
        if misses {
            return 0.0;
        }
        width * (hi - lo).length().min(diagonal) * (1.0 + U4)
    }

    /// A second bound on the area of [`Clip::band`]'s sliver, from the
    /// lines alone (the vertices' errors left out, which are large where
    /// nearly parallel lines meet): the sliver lies where `σ · line ≥ −(δ
    /// + e)` and, for every other line cut by, `line_j ≥ −(δ_j + e)` (`e`
    /// the computed vertices' distance from their lines, 0 for the exact
    /// image) — for one other line nearly opposite to this one, a wedge
    /// whose width `A + B t` is linear along the line; its area over the
    /// light's circumscribed disk (radius `ρ`: `|t| ≤ ρ`) is the integral
    /// of `max(0, A + B t)`. The least over the other lines; infinite where
    /// none is nearly opposite. The rounding of the normalised lines
    /// (a few ulps of each term) is added to `A`.
    fn wedge(&self, slot: usize, line: &Line, sigma: f64, e: f64) -> f64 {
        const SLACK: f64 = 64.0 * f64::EPSILON;
        let rho = self.disk.unwrap_or(SQRT_2);
        let unit = |l: &Line, s: f64| {
            let h = l.a.hypot(l.b);
            (DVec2::new(s * l.a / h, s * l.b / h), s * l.c / h)
        };
        let (n, c) = unit(line, sigma);
        let delta = line.tight + e;
        let mut least = f64::INFINITY;
        for (j, other) in self.lines.iter().enumerate() {
            let Some(other) = other.filter(|_| j != slot) else {
                continue;
            };
            let (m, d) = unit(&other, 1.0);
            // m = μ n + ν n⊥; x = s n + t n⊥: s ≥ −c − δ and
            // μ s + ν t ≥ −d − δⱼ, so for μ < 0 the width in s is
            // (d + δⱼ + ν t) / (−μ) + c + δ.
            let (mu, nu) = (m.dot(n), -m.perp_dot(n));
            if mu >= -0.5 || mu.is_nan() {
                continue;
            }
            let dj = other.tight + e;
            let a = (d + dj) / -mu + c + delta;
            let b = nu / -mu;
            let slack = SLACK * ((d.abs() + dj) / -mu + c.abs() + delta + rho * (1.0 + b.abs()));
            let a = a + slack;
            let (y0, y1) = (a - b * rho, a + b * rho);
            let area = if y0 <= 0.0 && y1 <= 0.0 {
                0.0
            } else if y0 >= 0.0 && y1 >= 0.0 {
                2.0 * rho * a
            } else {
                y0.max(y1).powi(2) / (2.0 * b.abs())
            };
            if area.is_finite() {
                least = least.min(area * (1.0 + SLACK));
            }
        }
        least
    }

    /// The point where the lines `l` and `e` meet, and a bound on its
    /// error, from the two lines alone.
    fn meet(
        &self,
        l: On,
        e: On,
        corner: &mut impl FnMut(usize) -> Option<(DVec2, f64)>,
    ) -> (DVec2, f64) {
        let line = |id: On| match id {
            On::Cone(i) => self.lines[usize::from(i)],
            On::Plane => self.lines[3],
            On::Side(_) => None,
        };
        match (l, e) {
            (On::Side(s), other) | (other, On::Side(s)) => match line(other) {
                Some(m) => side_crossing(&m, s, self.half),
                // Two sides meet at a corner of the square.
                None => (square_corner(l, e, self.half), 0.0),
            },
            (On::Cone(i), On::Cone(j)) => {
                // The planes through p and two edges meet along the ray
                // through their common corner.
                let k = 3 - usize::from(i) - usize::from(j);
                match corner(k) {
                    Some(at) => at,
                    None => cramer(&line(l).expect("cut"), &line(e).expect("cut")),
                }
            }
            _ => cramer(&line(l).expect("cut"), &line(e).expect("cut")),
        }
    }
}

/// A bound on the distance from `q` to the line an image's edge lies on:
/// on a side of the square `|X|, |Y| ≤ half`, the coordinate's distance
/// from `±half` (0 for every vertex constructed there, which keeps it
/// exactly; measured all the same, so that no edge is taken on a side it
/// does not run along); else [`distance`] from its line.
fn distance_from(id: On, line: &Option<Line>, q: DVec2, half: f64) -> f64 {
    match id {
        On::Side(0) => (q.y + half).abs(),
        On::Side(1) => (q.x - half).abs(),
        On::Side(2) => (q.y - half).abs(),
        On::Side(_) => (q.x + half).abs(),
        _ => line.as_ref().map_or(0.0, |l| distance(l, q)),
    }
}

/// A bound on the distance from `q` to the line: the rounded value over
/// the larger coefficient (at most the gradient's length), its rounding
/// included.
pub(super) fn distance(line: &Line, q: DVec2) -> f64 {
    ((line.at(q).abs() + line.rounding(q)) / line.norm()) * (1.0 + 4.0 * f64::EPSILON)
}

/// Where the line crosses side `s` of the square `|X|, |Y| ≤ h` (bottom,
/// right, top, left), from its coefficients alone (the same bits for the
/// line negated), clamped to the side; and a bound on its error: the
/// line's own moved along the side (by `|(a, b)| / |b|` for a vertical
/// side), and the rounding of the quotient.
pub(super) fn side_crossing(m: &Line, s: u8, h: f64) -> (DVec2, f64) {
    let (fixed, along_x) = match s {
        0 => (-h, true),
        1 => (h, false),
        2 => (h, true),
        _ => (-h, false),
    };
    // On a horizontal side y = fixed: x = −(b·fixed + c) / a; on a vertical
    // one x = fixed: y = −(a·fixed + c) / b.
    let (num, den, across) = if along_x {
        (m.b * fixed + m.c, m.a, m.b)
    } else {
        (m.a * fixed + m.c, m.b, m.a)
    };
    let t = (-num / den).clamp(-h, h);
    let err = m.err * (den.abs() + across.abs()) / den.abs()
        + 2.0 * f64::EPSILON * ((across * fixed).abs() + m.c.abs()) / den.abs()
        + f64::EPSILON * t.abs();
    let q = if along_x {
        DVec2::new(t, fixed)
    } else {
        DVec2::new(fixed, t)
    };
    (q, if err.is_finite() { err } else { f64::INFINITY })
}

/// The corner of the square where the sides `l` and `e` meet.
pub(super) fn square_corner(l: On, e: On, h: f64) -> DVec2 {
    let mut q = DVec2::ZERO;
    for id in [l, e] {
        match id {
            On::Side(0) => q.y = -h,
            On::Side(1) => q.x = h,
            On::Side(2) => q.y = h,
            On::Side(3) => q.x = -h,
            _ => {}
        }
    }
    q
}

/// Where two lines meet (Cramer's rule), and a bound on its error: the
/// lines' own over the sine of their angle, and the roundings of the
/// three 2×2 determinants.
pub(super) fn cramer(l1: &Line, l2: &Line) -> (DVec2, f64) {
    let det = l1.a * l2.b - l2.a * l1.b;
    let q = DVec2::new(
        (l1.b * l2.c - l2.b * l1.c) / det,
        (l1.c * l2.a - l2.c * l1.a) / det,
    );
    let n1 = l1.a.abs() + l1.b.abs();
    let n2 = l2.a.abs() + l2.b.abs();
    let perm = (l1.a * l2.b).abs() + (l2.a * l1.b).abs();
    let err = (l1.err + l2.err) * n1 * n2 / det.abs()
        + 4.0
            * f64::EPSILON
            * ((l1.b * l2.c).abs()
                + (l2.b * l1.c).abs()
                + (l1.c * l2.a).abs()
                + (l2.c * l1.a).abs()
                + q.abs().max_element() * perm)
            / det.abs();
    if q.is_finite() && err.is_finite() {
        (q, err)
    } else {
        (DVec2::ZERO, f64::INFINITY)
    }
}

/// The point where the segment `a b` crosses a line with values `fa`,
/// `fb` of strictly opposite signs at its ends; symmetric in its
/// arguments. Measured from the end nearer the line (`t ≤ ½`), so that the
/// rounding is relative to the distance from that end.
pub(super) fn crossing(a: DVec2, fa: f64, b: DVec2, fb: f64) -> DVec2 {
    let (a, fa, b, fb) = if fa.abs() <= fb.abs() {
        (a, fa, b, fb)
    } else {
        (b, fb, a, fa)
    };
    let t = (fa / (fa - fb)).clamp(0.0, 1.0);
    a + (b - a) * t
}

//! A triangle projected onto the light's plane: its corners' images on
//! the fast path, else its half-planes clipping the square around the light.

use super::clip::{Clip, Line, On};
use super::image::{Image, Polygon};
use super::AreaView;
use crate::kernel::predicate::{orient2d, orient3d, Sign};
use crate::kernel::receiver_view::bounded::{det3_exact, max_abs, Bounded, Cross, Row};
use crate::kernel::receiver_view::union::Measure;
use glam::{DVec2, DVec3};

impl AreaView {
    /// The image of a triangle on the light's plane: the light points it
    /// hides from `p` form the image's interior intersected with the light.
    /// Cut to the square `|X|, |Y| ≤ half` around the light (`half` is 1.5
    /// for a disk, 1 for a rect), counter-clockwise; empty when the
    /// triangle hides nothing there (it lies behind `p` or beyond the light,
    /// its plane holds `p`, or it has a non-finite corner).
    #[must_use]
    pub fn image(&self, tri: &[DVec3; 3]) -> Image {
        match self.polygon::<true>(tri) {
            Polygon::Corners([a, b, c], [ea, eb, ec]) => match orient2d(a, b, c) {
                Sign::Positive => Image::from_slice::<true>(&[a, b, c], &[ea, eb, ec]),
                Sign::Negative => Image::from_slice::<true>(&[a, c, b], &[ea, ec, eb]),
                Sign::Zero => Image::EMPTY,
            },
            Polygon::Clipped(image) => image,
        }
    }

    /// One corner's image (`d` its row from `p`) and a bound on its error,
    /// if the corner lies certainly in front of `p`, and its depth's
    /// rounded value (`sgn · det[d, f₀, f₁]`, with its bound): the point
    /// where the ray from `p` through the corner meets the plane, within
    /// [`TOLERANCE`] where it lies in the square (exact determinants where
    /// the rounded ones are not that close). With `refine` false, the
    /// rounded image only (`exact` false where it is not within the
    /// tolerance, or its depth is uncertain).
    #[inline(always)]
    fn corner<const B: bool>(&self, d: &Row, refine: bool) -> CornerImage {
        let direct = &self.direct;
        let [wx, wy, wz] = direct.w;
        let d_max = max_abs(d.r);
        let z = wz.dot(d.r, d_max).signed(direct.sgn);
        let (nx, ny) = (wx.dot(d.r, d_max), wy.dot(d.r, d_max));
        let first = self.corner_from(nx, ny, z);
        let settled = match first {
            Some((q, err)) => err <= TOLERANCE || q.abs().max_element() - err > self.half,
            None => false,
        };
        if settled || !refine {
            // Decided on the cheap bounds, in both paths alike (every
            // choice made from them is the same with or without the
            // bound); the bound reports the closer ones.
            let tight = match first {
                Some((_, err)) if B => {
                    let closer = |w: &Cross, b: Bounded| Bounded {
                        bound: w.precise(d.r),
                        ..b
                    };
                    let z = closer(&wz, z);
                    self.corner_from(closer(&wx, nx), closer(&wy, ny), z)
                        .map_or(err, |(_, closer)| closer.min(err))
                }
                Some((_, err)) => err,
                None => f64::INFINITY,
            };
            return CornerImage {
                at: first,
                tight,
                z,
                settled,
            };
        }
        let (c, f0, f1) = (&self.c, &self.rows[0], &self.rows[1]);
        let z = det3_exact(d, f0, f1).signed(direct.sgn);
        let at = self.corner_from(det3_exact(c, d, f1), det3_exact(c, d, f0), z);
        // Beyond the exact arithmetic's range, the rounded image.
        let at = at.or(first);
        CornerImage {
            at,
            tight: at.map_or(f64::INFINITY, |(_, err)| err),
            z,
            settled: true,
        }
    }

    /// The corner's image from the determinants `nx = det[c, d, f₁]`, `ny
    /// = det[c, d, f₀]` and its depth `z = sgn · det[d, f₀, f₁]`, with a
    /// bound on its error; `None` unless `z` is certainly positive (above
    /// twice its bound).
    #[inline(always)]
    fn corner_from(&self, nx: Bounded, ny: Bounded, z: Bounded) -> Option<(DVec2, f64)> {
        if z.value <= 2.0 * z.bound || z.value.is_nan() {
            return None;
        }
        let sz = self.direct.sgn / z.value;
        let (x, y) = (nx.value * sz, -ny.value * sz);
        let [m00, m01, m11] = self.m;
        let q = DVec2::new(m00 * x + m01 * y, m11 * y);
        // First order in the determinants' bounds (z's bound is below half
        // of z, so the quotient's relative error is below twice it), and
        // the roundings of the quotients and the map.
        let rel = z.bound / (z.value - z.bound);
        let ex = (nx.bound * sz.abs() + x.abs() * rel) * 1.01 + x.abs() * f64::EPSILON;
        let ey = (ny.bound * sz.abs() + y.abs() * rel) * 1.01 + y.abs() * f64::EPSILON;
        let err = (m00.abs() * ex + m01.abs() * ey).max(m11.abs() * ey)
            + 2.0 * f64::EPSILON * q.abs().max_element();
        (q.is_finite() && err.is_finite()).then_some((q, err))
    }

    /// The half-plane of light points `x` with `det[u, v, x − o] ≥ 0`
    /// (rows `u`, `v` relative to `o`, `center_o` the row `center − o`),
    /// with coefficients within [`TOLERANCE`] (exact determinants where
    /// the rounded ones are not), or `Err` when its line certainly misses
    /// the square (then the square lies wholly on one side; `Err(true)`
    /// inside).
    fn line<const B: bool>(&self, u: &Row, v: &Row, center_o: &Row) -> Result<Line, bool> {
        let mut cross = Cross::of(u.r, v.r);
        if cross.cancels() {
            cross = Cross::compensated(u, v);
        }
        let [f0, f1] = &self.rows;
        let [m0, m1] = self.rows_max;
        let (a, b, c) = (
            cross.dot(f0.r, m0),
            cross.dot(f1.r, m1),
            cross.dot(center_o.r, max_abs(center_o.r)),
        );
        let line = self.in_view(a, b, c);
        if let Some(settled) = self.settled(line) {
            // Decided on the cheap bounds, in both paths alike (`err`
            // takes every decision); the bound reports the closer ones.
            return match settled {
                Ok(line) if B => Ok(Line {
                    tight: self
                        .in_view(
                            Bounded {
                                bound: cross.precise(f0.r),
                                ..a
                            },
                            Bounded {
                                bound: cross.precise(f1.r),
                                ..b
                            },
                            Bounded {
                                bound: cross.precise(center_o.r),
                                ..c
                            },
                        )
                        .err
                        .min(line.err),
                    ..line
                }),
                other => other,
            };
        }
        let exact = self.in_view(
            det3_exact(u, v, f0),
            det3_exact(u, v, f1),
            det3_exact(u, v, center_o),
        );
        // Beyond the exact arithmetic's range (coordinates far outside the
        // domain, whose expansions overflow), the rounded line stands.
        let line = if exact.a.is_finite() && exact.b.is_finite() && exact.c.is_finite() {
            exact
        } else {
            line
        };
        self.settled(line).unwrap_or(Ok(line))
    }

    /// Whether the half-plane `s · line ≥ 0` (`s = ±1`) certainly leaves
    /// out the whole light (the unit disk, or the square `[−1, 1]²`) by more
    /// than [`MISS_MARGIN`]: then the triangle's image hides none of it, and
    /// its clipping is skipped. The largest value of `s · line` over the
    /// light (`s c + |(a, b)|` on the disk, `s c + |a| + |b|` on the
    /// square), rounded up, plus the line's own error (within `err ·
    /// max(|a|, |b|)` of the exact line's values over the square), below
    /// minus the margin. Most images of a frame that are clipped at all lie
    /// beside the light (culling keeps whatever meets the pyramid over the
    /// square `|X|, |Y| ≤ half`).
    #[inline(always)]
    fn excludes_light(&self, line: &Result<Line, bool>, s: f64) -> bool {
        let line = match line {
            Ok(line) => line,
            // The line misses the square: all or nothing of it is kept.
            &Err(inside) => return (s > 0.0) != inside,
        };
        let (a, b) = (line.a.abs(), line.b.abs());
        let reach = match self.measure {
            Measure::Disk(r) => r * a.hypot(b),
            Measure::Square => a + b,
        };
        let top = s * line.c + reach;
        let rounding = 4.0 * f64::EPSILON * (line.c.abs() + reach);
        top + rounding + 2.0 * (line.err + MISS_MARGIN) * a.max(b) < 0.0
    }

    /// `line` if it is within [`TOLERANCE`], `Err` if it certainly misses
    /// the square (the centre's side: the distance from the centre to the
    /// line, at least `|c| / (√2 max(|a|, |b|))`, beyond half the square's
    /// diagonal and the line's error), `None` if neither.
    #[inline(always)]
    fn settled(&self, line: Line) -> Option<Result<Line, bool>> {
        let norm = line.norm();
        if line.c.abs() > (2.0 * self.half + 1.5 * line.err) * norm {
            Some(Err(line.c > 0.0))
        } else if line.err <= TOLERANCE {
            Some(Ok(line))
        } else {
            None
        }
    }

    /// The line `A X + B Y + C = 0` in oblique coordinates, in the view's:
    /// `(a, b) = (A, B) M⁻¹`, and the bound on its distance from the exact
    /// line over the square.
    #[inline(always)]
    fn in_view(&self, a: Bounded, b: Bounded, c: Bounded) -> Line {
        let [i00, i01, i11] = self.inv;
        let (ta, tb) = (a.value * i01, b.value * i11);
        let line = Line {
            a: a.value * i00,
            b: ta + tb,
            c: c.value,
            err: 0.0,
            tight: 0.0,
        };
        let ea = a.bound * i00.abs() + f64::EPSILON * line.a.abs();
        let eb = a.bound * i01.abs() + b.bound * i11.abs() + f64::EPSILON * (ta.abs() + tb.abs());
        let norm = line.norm();
        let shift = c.bound + self.half * (ea + eb);
        // Beyond a quarter of the coefficients' size the bound is not
        // first order: infinite (the caller then asks the exact values).
        let err = if ea + eb <= 0.25 * norm {
            shift / norm * 1.5
        } else {
            f64::INFINITY
        };
        Line {
            err,
            tight: err,
            ..line
        }
    }

    /// The image of a triangle: its projected corners on the fast path,
    /// else the square cut by the four half-planes.
    pub(super) fn polygon<const B: bool>(&self, tri: &[DVec3; 3]) -> Polygon {
        if !tri.iter().all(|v| v.is_finite()) {
            return Polygon::Clipped(Image::EMPTY);
        }
        // σ: the sign of det[a − p, b − p, c − p]. Zero: the plane holds p,
        // the image is a segment or a point.
        let sigma = match orient3d(tri[0], tri[1], tri[2], self.p) {
            Sign::Positive => 1.0,
            Sign::Negative => -1.0,
            Sign::Zero => return Polygon::Clipped(Image::EMPTY),
        };
        // The fast path: every corner certainly between p and the light's
        // plane and inside the square. Its corners' images serve the
        // clipped path too (where two cone planes meet, at a corner).
        // The corners' images, settled (within the tolerance, or refined)
        // or not yet.
        let mut corners: [Option<Option<(DVec2, f64)>>; 3] = [None; 3];
        let mut tight = [f64::INFINITY; 3];
        let depth = self.direct.depth;
        let mut fast = self.fast;
        for (k, &v) in tri.iter().enumerate() {
            if !fast {
                break;
            }
            let d = Row::diff(v, self.p);
            // Rounded first: a corner near p's depth, or outside the
            // square, ends the fast path without being refined (the
            // clipped path asks for it only if two cone planes meet there).
            let mut corner = self.corner::<B>(&d, false);
            let plausible = |c: &CornerImage| {
                let before = depth.value - c.z.value
                    > (depth.bound + c.z.bound) * 1.01 + f64::EPSILON * depth.value;
                before
                    && c.at.is_some_and(|(q, err)| {
                        q.x.abs() + err.min(1.0) < self.half && q.y.abs() + err.min(1.0) < self.half
                    })
            };
            if !corner.settled && corner.at.is_some() && plausible(&corner) {
                corner = self.corner::<B>(&d, true);
            }
            fast = corner.settled && plausible(&corner) && {
                let (q, err) = corner.at.expect("plausible");
                q.x.abs() + err < self.half && q.y.abs() + err < self.half
            };
            if corner.settled {
                corners[k] = Some(corner.at);
                tight[k] = corner.tight;
            }
        }
        if fast {
            let at = corners.map(|c| c.flatten().expect("every corner projected"));
            return Polygon::Corners(at.map(|a| a.0), tight);
        }
        // The cone: for the edge (j, k) opposite corner i, the plane through
        // p and the edge, oriented toward corner i (σ · det[qⱼ − p, qₖ − p,
        // qᵢ − p] = σ², a cyclic shift of the rows). The edge's ends are
        // taken in a canonical order, so that the two triangles sharing an
        // edge cut their images along the same line, bit for bit.
        let mut lines = [(Err(true), 0.0); 4];
        for (i, (j, k)) in [(1, 2), (2, 0), (0, 1)].into_iter().enumerate() {
            let (u, v, s) = if lexicographic(tri[j], tri[k]) {
                (tri[j], tri[k], sigma)
            } else {
                (tri[k], tri[j], -sigma)
            };
            // det[u − p, v − p, ·] = det[u − p, v − u, ·]: the edge's own
            // direction cancels far less than a second direction from p
            // (small or distant edges subtend small angles).
            let (ru, e) = (Row::diff(u, self.p), Row::diff(v, u));
            let line = self.line::<B>(&ru, &e, &self.c);
            if self.excludes_light(&line, s) {
                return Polygon::Clipped(Image::EMPTY);
            }
            lines[i] = (line, s);
        }
        // Strictly beyond the triangle's plane: σ · det[q₁ − q₀, q₂ − q₀,
        // x − q₀] > 0 (at x = p it is −σ).
        let (e1, e2) = (Row::diff(tri[1], tri[0]), Row::diff(tri[2], tri[0]));
        let line = self.line::<B>(&e1, &e2, &Row::diff(self.center, tri[0]));
        if self.excludes_light(&line, sigma) {
            return Polygon::Clipped(Image::EMPTY);
        }
        lines[3] = (line, sigma);
        // Every line leaves some of the light: cut the square by each.
        let mut clip = Clip::new(self.half, self.measure);
        for (i, &(line, s)) in lines[..3].iter().enumerate() {
            if !clip.cut(On::Cone(i as u8), line, s, |corner| {
                *corners[corner].get_or_insert_with(|| {
                    self.corner::<B>(&Row::diff(tri[corner], self.p), true).at
                })
            }) {
                return Polygon::Clipped(clip.finish::<B>());
            }
        }
        let (line, s) = lines[3];
        clip.cut(On::Plane, line, s, |_| None);
        Polygon::Clipped(clip.finish::<B>())
    }
}

/// The largest error, in the view's coordinates (the light's radius or
/// half-width is 1), of an image's line or corner above which its
/// determinants are evaluated exactly.
pub(super) const TOLERANCE: f64 = 1.0 / (1u64 << 43) as f64;

/// How far (in the view's coordinates) a half-plane must leave out the
/// whole light for [`AreaView::excludes_light`] to skip the triangle: far
/// beyond any vertex's error, so that nothing the clipping would have kept
/// can lie in the light.
pub(super) const MISS_MARGIN: f64 = 1.0 / (1u64 << 20) as f64;

/// A corner's image, if it lies certainly in front of `p`, with its error
/// bound; its depth `sgn · det[d, f₀, f₁]`; and whether the image is
/// settled (within the tolerance, certainly outside the square, or
/// refined).
#[derive(Clone, Copy, Debug)]
pub(super) struct CornerImage {
    at: Option<(DVec2, f64)>,
    /// The closer bound on the image's error, for the certified bound
    /// (`at`'s own error, from the cheap bounds, takes the decisions).
    tight: f64,
    z: Bounded,
    settled: bool,
}

/// Whether `a` precedes `b` in lexicographic order of coordinates.
pub(super) fn lexicographic(a: DVec3, b: DVec3) -> bool {
    (a.x, a.y, a.z) <= (b.x, b.y, b.z)
}

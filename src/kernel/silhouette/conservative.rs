//! Conservative silhouettes for a sphere light
//! ([`MeshTopology::potential_silhouettes`]): every edge that may be a
//! silhouette edge from some point of a ball, each face classified against
//! the ball with a derived rounding bound.

use super::{MeshTopology, SilhouetteError};
use glam::DVec3;

/// Per-face classification against a ball.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum BallFacing {
    /// Front-facing from every point of the ball.
    Front,
    /// Back-facing or edge-on from every point of the ball.
    Back,
    /// Depends on the point.
    Uncertain,
}

impl MeshTopology {
    /// Appends to `out`, in increasing order, the indices of the edges that
    /// may be silhouette edges from some point of the closed ball with centre
    /// `center` and radius `radius` (a sphere light): a conservative superset
    /// of [`silhouettes_from_point`](Self::silhouettes_from_point) for every
    /// `x` in the ball. `radius = 0` bounds the silhouettes from `center`.
    /// `out` is not cleared.
    ///
    /// Each face is classified as front-facing from the whole ball,
    /// back-facing (or edge-on) from the whole ball, or uncertain — its plane
    /// meets the ball. With `n = (b − a) × (c − a)` and `s = n · (center − a)`
    /// the face is surely front when `s > r‖n‖` and surely back when
    /// `s ≤ −r‖n‖`. The rounded `s` and `‖n‖` are bracketed by a derived
    /// forward error bound (`γ₁₂` times the absolute-value permanent of `s`,
    /// plus a gradual-underflow term, derived at `classify_face` in the source), so an uncertain
    /// face is never classified as certain, for every finite input.
    /// An edge is reported when one of its faces is uncertain, or when its
    /// multiplicity from the certain facings is non-zero.
    ///
    /// Tightness: a face is reported uncertain only when its plane passes
    /// within `r + δ` of the centre, with `δ` about `1e-15` relative to the
    /// coordinates. The edge rule is the exact answer for each face taken
    /// alone; it over-reports an edge whose faces are both uncertain but face
    /// the same way from every point of the ball (their planes meet the ball
    /// but their dihedral wedge does not). The report (`tests/silhouette.rs`,
    /// `SOFTSHADOW_PRINT_ACCURACY=1`) measures the ratio of reported edges to
    /// edges seen as silhouettes from sampled light points.
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::PositionCount`] when `positions.len()` is not the
    /// vertex count, [`SilhouetteError::InvalidSphere`] for a non-finite
    /// centre or a radius that is negative or not finite; nothing is appended
    /// then.
    pub fn potential_silhouettes_into<P, X>(
        &self,
        positions: &[P],
        center: X,
        radius: f64,
        out: &mut Vec<u32>,
    ) -> Result<(), SilhouetteError>
    where
        P: Copy + Into<DVec3>,
        X: Into<DVec3>,
    {
        self.check_positions(positions)?;
        let center: DVec3 = center.into();
        if !center.is_finite() || !radius.is_finite() || radius < 0.0 {
            return Err(SilhouetteError::InvalidSphere);
        }
        for edge in 0..self.edges.len() {
            let m = self.multiplicity(edge, positions, |[a, b, c]| {
                match classify_face(a, b, c, center, radius) {
                    BallFacing::Front => Some(1),
                    BallFacing::Back => Some(-1),
                    BallFacing::Uncertain => None,
                }
            });
            // Uncertain (None) or a contour for every point of the ball.
            if m != Some(0) {
                out.push(edge as u32);
            }
        }
        Ok(())
    }

    /// [`potential_silhouettes_into`](Self::potential_silhouettes_into) into
    /// a new `Vec`.
    ///
    /// # Errors
    ///
    /// As [`potential_silhouettes_into`](Self::potential_silhouettes_into).
    pub fn potential_silhouettes<P, X>(
        &self,
        positions: &[P],
        center: X,
        radius: f64,
    ) -> Result<Vec<u32>, SilhouetteError>
    where
        P: Copy + Into<DVec3>,
        X: Into<DVec3>,
    {
        let mut out = Vec::new();
        self.potential_silhouettes_into(positions, center, radius, &mut out)?;
        Ok(out)
    }
}

use crate::kernel::footprint::f64::gamma;

/// The smallest positive subnormal: the absolute error bound of a rounded
/// product or quotient in gradual underflow is half of it.
const ETA: f64 = f64::from_bits(1);

/// The facing of triangle `(a, b, c)` from every point of the ball
/// `(center, r)`, conservative under rounding.
///
/// Error analysis (Higham's `θ_n` notation, `|θ_n| ≤ γ(n)`): with
/// `u = b − a`, `v = c − a`, `d = center − a` each rounded once,
/// `s = fl(Σ_i n̂_i d̂_i)`, `n̂_x = fl(û_y v̂_z − û_z v̂_y)` (cyclically), every
/// monomial `u_j v_k d_i` of the exact `n · d` reaches `s` multiplied by at
/// most 8 factors `(1 + δ)` (3 differences, 2 products, 1 subtraction, 2
/// additions), so `|s − n·d| ≤ γ(8) · Σ|u_j v_k d_i|`. The computed permanent
/// `perm` of those monomials is itself low by at most a factor `1 − γ(8)`
/// (3 rounded factors, 5 operations), so `γ(8)/(1 − γ(8)) · perm ≤ γ(12) ·
/// perm` covers it with room for the rounding of the bound itself. Likewise
/// `|n̂_i − n_i| ≤ γ(4)` times the component's permanent `Q_i`, and
/// `‖n‖ ≤ ‖n̂‖ + Σ|n̂_i − n_i|`, with the rounded `‖n̂‖` raised by `γ(4)`
/// (or replaced by `‖n̂‖₁` when `n̂ · n̂` could be subnormal). Underflow adds
/// at most `ETA` per rounded product; the `ETA` terms bound its propagation.
/// The final comparisons raise the threshold `E + r·N` by `γ(3)` for its own
/// two roundings.
fn classify_face(a: DVec3, b: DVec3, c: DVec3, center: DVec3, r: f64) -> BallFacing {
    let u = b - a;
    let v = c - a;
    let d = center - a;
    let n = u.cross(v);
    let s = n.dot(d);
    let q = DVec3::new(
        (u.y * v.z).abs() + (u.z * v.y).abs(),
        (u.z * v.x).abs() + (u.x * v.z).abs(),
        (u.x * v.y).abs() + (u.y * v.x).abs(),
    );
    let d_abs = d.abs();
    let perm = q.dot(d_abs);
    let err_s = gamma(12) * perm + 2.0 * ETA * (d_abs.element_sum() + 2.0);
    let n_abs = n.abs();
    let norm = if n_abs.max_element() < 2f64.powi(-500) {
        n_abs.element_sum()
    } else {
        n.length() * (1.0 + gamma(4))
    };
    let norm_up = norm + gamma(8) * q.element_sum() + 4.0 * ETA;
    let threshold = (err_s + r * norm_up) * (1.0 + gamma(3));
    // NaN (overflowed magnitudes: inf − inf) fails both comparisons: uncertain.
    if s > threshold {
        BallFacing::Front
    } else if s <= -threshold {
        BallFacing::Back
    } else {
        BallFacing::Uncertain
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classify_face_brackets_the_plane() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y); // normal +z
        let f = |z: f64, r: f64| classify_face(a, b, c, DVec3::new(0.3, 0.3, z), r);
        assert_eq!(f(2.0, 1.0), BallFacing::Front);
        assert_eq!(f(-2.0, 1.0), BallFacing::Back);
        // Tangent balls and a centre in the plane are within the rounding
        // bracket: the conservative answer is "uncertain", never a guess.
        assert_eq!(f(1.0, 1.0), BallFacing::Uncertain);
        assert_eq!(f(-1.0, 1.0), BallFacing::Uncertain);
        assert_eq!(f(0.0, 0.0), BallFacing::Uncertain);
        assert_eq!(f(1.0, 1.0 - 1e-12), BallFacing::Front);
        assert_eq!(f(-1.0, 1.0 - 1e-12), BallFacing::Back);
        // NaN from overflow (∞ − ∞) is uncertain, not a facing.
        let huge = classify_face(a, DVec3::X * 1e300, DVec3::Y * 1e300, DVec3::Z * 1e300, 1.0);
        assert_eq!(huge, BallFacing::Uncertain);
    }
}

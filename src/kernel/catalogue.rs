//! The kernel catalogue: each kernel family's contract declared once — its
//! documented domain, its error budgets, the stiff cases it is measured on.
//!
//! The tests assert these budgets against high-precision evaluations, the
//! fuzz targets assert them on fuzzed input, `softshadow selfcheck` checks
//! each family on a closed form within them, and the stability suite
//! (`softshadow stability`) measures each family on exactly the stiff
//! cases listed here (a unit test holds it to that). A new kernel family is
//! one entry of [`FAMILIES`]; a changed bound is one edit of its
//! [`Budget`].
//!
//! A budget holds in both precisions, in the units of each: `ε` and ulps
//! are those of the precision evaluated (`2⁻⁵²` for `f64`, `2⁻²³` for
//! `f32`). The measured maxima behind each budget are in
//! `docs/accuracy/kernels.md`.

/// The unit a [`Budget`] is stated in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unit {
    /// Absolute area error over `r²`, in `ε` (the natural unit of a
    /// visibility fraction `area/πr²`).
    EpsR2,
    /// Absolute error in `ε`.
    Eps,
    /// Error relative to the true value, in `ε`.
    EpsRelative,
    /// Ulps of the true result.
    Ulp,
    /// Wrong decisions (exact kernels: the budget is 0).
    Decisions,
    /// Multiples of a bound derived for each input (the kernel's docs
    /// state it).
    DerivedBound,
}

impl Unit {
    /// How the unit follows a number (`3ε·r²`, `1.5 ulp`).
    #[must_use]
    pub const fn symbol(self) -> &'static str {
        match self {
            Unit::EpsR2 => "ε·r²",
            Unit::Eps => "ε",
            Unit::EpsRelative => "ε (relative)",
            Unit::Ulp => " ulp",
            Unit::Decisions => " wrong decisions",
            Unit::DerivedBound => " × the derived bound",
        }
    }
}

/// A family of stiff input: what the stability suite stresses a kernel
/// with, and what the generators of `softshadow::arbitrary` bias toward.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Stiff {
    /// The configuration moved far from the origin.
    FarOffset,
    /// Tiny and huge lights against the rest of the scene.
    LightSize,
    /// Grazing views: thin slivers, light near the horizon, points close
    /// to a line.
    Grazing,
    /// Contact: receivers just behind an occluder, parameters at the ends
    /// of their range.
    Contact,
    /// Nearly coincident edges.
    CoincidentEdges,
    /// Many occluders on one another.
    DeepOverlap,
    /// Ordinary input spread over the whole domain.
    Uniform,
    /// Points where the answer is exact in floating point.
    ExactPoints,
    /// An exact identity of the function (`F(t) + F(1 − t) = 1`).
    Symmetry,
}

impl Stiff {
    /// The name the stability suite's tables use (`far offset`).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Stiff::FarOffset => "far offset",
            Stiff::LightSize => "light size",
            Stiff::Grazing => "grazing",
            Stiff::Contact => "contact",
            Stiff::CoincidentEdges => "coincident edges",
            Stiff::DeepOverlap => "deep overlap",
            Stiff::Uniform => "uniform",
            Stiff::ExactPoints => "exact points",
            Stiff::Symmetry => "symmetry",
        }
    }
}

/// One function's error budget: the largest error the tests, the fuzz
/// targets and the self-check accept.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    /// The function, as `family::function` (`disk::segment_disk_area`).
    pub function: &'static str,
    /// What the budget is for, where the function has several.
    pub quantity: &'static str,
    /// The bound, in [`unit`](Self::unit)s.
    pub bound: f64,
    /// The unit of [`bound`](Self::bound).
    pub unit: Unit,
    /// The generator of `softshadow::arbitrary` the tests measure it on.
    pub generator: &'static str,
}

impl Budget {
    /// The bound as the docs state it: `3ε·r²`, `1.5 ulp`.
    #[must_use]
    pub fn stated(&self) -> String {
        format!("{}{}", self.bound, self.unit.symbol())
    }
}

/// One kernel family's contract.
#[derive(Clone, Copy, Debug)]
pub struct Family {
    /// The module under `kernel` (`disk`).
    pub name: &'static str,
    /// The documented domain, in one sentence.
    pub domain: &'static str,
    /// Its budgets, one per function and quantity.
    pub budgets: &'static [Budget],
    /// The stiff cases the stability suite measures it on.
    pub stiff: &'static [Stiff],
}

/// `kernel::predicate`: exact orientation tests.
pub mod predicate {
    use super::{Budget, Unit};

    /// `orient2d` and `orient3d`: exact signs.
    pub const ORIENT: Budget = Budget {
        function: "predicate::orient2d",
        quantity: "sign (and orient3d's)",
        bound: 0.0,
        unit: Unit::Decisions,
        generator: "near-collinear and near-coplanar points",
    };
}

/// `kernel::angle`: the portable `atan2`.
pub mod angle {
    use super::{Budget, Unit};

    /// `atan2`, against the true angle.
    pub const ATAN2: Budget = Budget {
        function: "angle::atan2",
        quantity: "angle",
        bound: 1.5,
        unit: Unit::Ulp,
        generator: "stiff_point",
    };
}

/// `kernel::disk`: areas of a disk cut by edges and polygons.
pub mod disk {
    use super::{Budget, Unit};

    /// `segment_disk_area`, for any edge length.
    pub const SEGMENT_DISK_AREA: Budget = Budget {
        function: "disk::segment_disk_area",
        quantity: "area",
        bound: 3.0,
        unit: Unit::EpsR2,
        generator: "disk_edge",
    };

    /// `polygon_disk_area`.
    pub const POLYGON_DISK_AREA: Budget = Budget {
        function: "disk::polygon_disk_area",
        quantity: "area",
        bound: 5.0,
        unit: Unit::EpsR2,
        generator: "polygon",
    };

    /// `circle_segment_occlusion`, absolute.
    pub const CIRCLE_SEGMENT_OCCLUSION: Budget = Budget {
        function: "disk::circle_segment_occlusion",
        quantity: "occluded fraction",
        bound: 1.0,
        unit: Unit::Eps,
        generator: "clipped_edge",
    };

    /// `circle_segment_occlusion` of thin full chords, relative.
    pub const THIN_CHORD: Budget = Budget {
        function: "disk::circle_segment_occlusion",
        quantity: "thin full chords",
        bound: 9.0,
        unit: Unit::EpsRelative,
        generator: "h = 1 − 10^[−15, −0.3]",
    };
}

/// `kernel::falloff`: the falloff curves across a penumbra.
pub mod falloff {
    use super::{Budget, Unit};
    use crate::kernel::falloff::Falloff;

    /// `bernstein`, normal results.
    pub const BERNSTEIN_NORMAL: Budget = Budget {
        function: "falloff::bernstein",
        quantity: "normal results",
        bound: 0.55,
        unit: Unit::Ulp,
        generator: "falloff_t",
    };

    /// `bernstein`, subnormal results included (they round twice).
    pub const BERNSTEIN: Budget = Budget {
        function: "falloff::bernstein",
        quantity: "every result",
        bound: 1.0,
        unit: Unit::Ulp,
        generator: "falloff_t",
    };

    /// `disk_edge_falloff`, every result.
    pub const DISK_EDGE_FALLOFF: Budget = Budget {
        function: "falloff::disk_edge_falloff",
        quantity: "every result",
        bound: 1.0,
        unit: Unit::Ulp,
        generator: "falloff_t",
    };

    /// `linear`: exact.
    pub const LINEAR: Budget = Budget {
        function: "falloff::eval",
        quantity: "Falloff::Linear",
        bound: 0.0,
        unit: Unit::Ulp,
        generator: "falloff_t",
    };

    /// The budget of a falloff curve, subnormal results included.
    #[must_use]
    pub const fn of(curve: Falloff) -> Budget {
        match curve {
            Falloff::Linear => LINEAR,
            Falloff::Bernstein => BERNSTEIN,
            Falloff::Exact => DISK_EDGE_FALLOFF,
        }
    }
}

/// `kernel::distortion`: SSOC's distortion and shadow intensity.
pub mod distortion {
    use super::{Budget, Unit};

    /// `max_distortion` (four roundings).
    pub const MAX_DISTORTION: Budget = Budget {
        function: "distortion::max_distortion",
        quantity: "distortion",
        bound: 4.0,
        unit: Unit::Ulp,
        generator: "distortion_case",
    };

    /// `penumbra_position` (two roundings).
    pub const PENUMBRA_POSITION: Budget = Budget {
        function: "distortion::penumbra_position",
        quantity: "position",
        bound: 2.0,
        unit: Unit::Ulp,
        generator: "distortion_case",
    };
}

/// `kernel::footprint`: the light's footprint on the light image plane.
pub mod footprint {
    use super::{Budget, Unit};

    /// `radius`, normal results (measured through `max_distortion`, which
    /// is exactly twice it).
    pub const RADIUS: Budget = Budget {
        function: "footprint::radius",
        quantity: "radius",
        bound: 4.0,
        unit: Unit::Ulp,
        generator: "distortion_case",
    };
}

/// `kernel::linear_light`: OESS's visible part of a segment light.
pub mod linear_light {
    use super::{Budget, Unit};

    /// `visible_part`'s fraction, against the rigorous bound derived in
    /// the module docs of `kernel::linear_light` (it grows only where the
    /// answer is ill-conditioned: a shadow line grazing the direction of an
    /// endpoint).
    pub const VISIBLE_PART: Budget = Budget {
        function: "linear_light::visible_part",
        quantity: "fraction",
        bound: 1.0,
        unit: Unit::DerivedBound,
        generator: "linear_light_case",
    };
}

/// `kernel::silhouette`: silhouette edges from a point.
pub mod silhouette {
    use super::{Budget, Unit};

    /// `silhouettes_from_point`: exact edge sets.
    pub const FROM_POINT: Budget = Budget {
        function: "silhouette::silhouettes_from_point",
        quantity: "edge set",
        bound: 0.0,
        unit: Unit::Decisions,
        generator: "any_mesh",
    };
}

/// `kernel::wedge`: penumbra wedges and quads.
pub mod wedge {
    use super::{Budget, Unit};

    /// `PenumbraWedge::contains` and `penumbra_quad`: conservative, no
    /// affected receiver left out.
    pub const CONTAINS: Budget = Budget {
        function: "wedge::PenumbraWedge::contains",
        quantity: "affected receivers missed",
        bound: 0.0,
        unit: Unit::Decisions,
        generator: "wedge_case",
    };

    /// The angle between an `f32` wedge plane and the `f64` plane of the
    /// same input, in `f32` ε, over well-conditioned `wedge_case` inputs
    /// (edge and its line ≥ 2 r from the centre, ≤ 100 r away, ≥ 0.1 off
    /// radial). The planes are built for a radius inflated by
    /// `32 ε ‖e − c‖` (the margin their verification needs), which tilts a
    /// tangent plane by about `32 ε ‖e − c‖ / (ρ z)`: the bulk of this
    /// number.
    pub const NORMAL_F32: Budget = Budget {
        function: "wedge::PenumbraWedge::new",
        quantity: "f32 plane normals against f64 (angle)",
        bound: 512.0,
        unit: Unit::Eps,
        generator: "wedge_case",
    };

    /// The relative difference of the `f32` and `f64` penumbra quad
    /// radius, in `f32` ε.
    pub const QUAD_RADIUS_F32: Budget = Budget {
        function: "wedge::penumbra_quad",
        quantity: "f32 radius against f64",
        bound: 16.0,
        unit: Unit::EpsRelative,
        generator: "light_frame_edge",
    };
}

use Stiff::{ExactPoints, FarOffset, Grazing, LightSize, Symmetry, Uniform};

/// Every kernel family with a numerical contract, in the order the tables
/// list them.
pub static FAMILIES: &[Family] = &[
    Family {
        name: "predicate",
        domain: "exact for every nonzero coordinate in [1e-140, 1e150] (orient2d) \
                 and [1e-90, 1e90] (orient3d); every finite f32 is inside both",
        budgets: &[predicate::ORIENT],
        stiff: &[],
    },
    Family {
        name: "angle",
        domain: "every finite x, y; NaN gives 0",
        budgets: &[angle::ATAN2],
        stiff: &[FarOffset, LightSize, Uniform, Grazing],
    },
    Family {
        name: "disk",
        domain: "finite points and r ≥ 0, a disk at most 1e100 (f64; 1e12 for f32) \
                 times smaller than the coordinates",
        budgets: &[
            disk::SEGMENT_DISK_AREA,
            disk::POLYGON_DISK_AREA,
            disk::CIRCLE_SEGMENT_OCCLUSION,
            disk::THIN_CHORD,
        ],
        stiff: &[FarOffset, LightSize, Grazing],
    },
    Family {
        name: "falloff",
        domain: "t in [0, 1]; 0 below, 1 above, 0 for NaN",
        budgets: &[
            falloff::BERNSTEIN_NORMAL,
            falloff::BERNSTEIN,
            falloff::DISK_EDGE_FALLOFF,
            falloff::LINEAR,
        ],
        stiff: &[Uniform, Stiff::Contact, Symmetry, Grazing, ExactPoints],
    },
    Family {
        name: "distortion",
        domain: "r ≥ 0, 0 < z_n < z_p ≤ +∞; 0 outside, never NaN",
        budgets: &[distortion::MAX_DISTORTION, distortion::PENUMBRA_POSITION],
        stiff: &[Stiff::Contact],
    },
    Family {
        name: "footprint",
        domain: "r ≥ 0, 0 < z_q < z_p ≤ +∞; 0 outside, never NaN",
        budgets: &[footprint::RADIUS],
        stiff: &[Stiff::Contact, LightSize, FarOffset],
    },
    Family {
        name: "linear_light",
        domain: "finite points, l ≠ r, f off the light's line; decisions exact in \
                 orient2d's domain",
        budgets: &[linear_light::VISIBLE_PART],
        stiff: &[FarOffset, Grazing, LightSize],
    },
    Family {
        name: "silhouette",
        domain: "coordinates of magnitude in [1e-90, 1e90] (orient3d's domain)",
        budgets: &[silhouette::FROM_POINT],
        stiff: &[FarOffset],
    },
    Family {
        name: "wedge",
        domain: "finite input, radius > 0, e0 ≠ e1, the edge outside the light",
        budgets: &[wedge::CONTAINS, wedge::NORMAL_F32, wedge::QUAD_RADIUS_F32],
        stiff: &[FarOffset, LightSize],
    },
];

/// The family called `name` (`disk`).
#[must_use]
pub fn family(name: &str) -> Option<&'static Family> {
    FAMILIES.iter().find(|f| f.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_budget_belongs_to_its_family_and_each_family_is_named_once() {
        for (i, f) in FAMILIES.iter().enumerate() {
            assert!(
                FAMILIES[..i].iter().all(|g| g.name != f.name),
                "{} twice",
                f.name
            );
            assert!(!f.budgets.is_empty(), "{} has no budget", f.name);
            for b in f.budgets {
                let prefix = b.function.split("::").next();
                assert_eq!(prefix, Some(f.name), "{} under {}", b.function, f.name);
                assert!(b.bound >= 0.0 && b.bound.is_finite(), "{b:?}");
            }
        }
    }

    #[test]
    fn a_budget_is_stated_as_the_docs_state_it() {
        let b = |bound, unit| Budget {
            bound,
            unit,
            ..disk::SEGMENT_DISK_AREA
        };
        assert_eq!(b(3.0, Unit::EpsR2).stated(), "3ε·r²");
        assert_eq!(b(1.5, Unit::Ulp).stated(), "1.5 ulp");
    }
}

//! Why a light could not be built ([`LightError`]) and why a receiver
//! cannot see its emitting measure ([`ReceiverError`]).

/// Why a light could not be built. A constructor checks every argument
/// and reports each one that is invalid: one fault as its own variant,
/// several as [`LightError::Several`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum LightError {
    /// A coordinate or the radius is NaN or infinite; the field is named.
    NonFinite {
        /// The offending field (`"center"`, `"radius"`, `"normal"`, …).
        field: &'static str,
    },
    /// The radius is zero or negative.
    NonPositiveRadius {
        /// The radius given.
        radius: f64,
    },
    /// A disk's normal is zero (any other finite normal is accepted,
    /// however long or short).
    ZeroNormal,
    /// A rect's half-axes are zero or parallel (no area; an area beyond
    /// the range of `f64`, large or small, is accepted).
    DegenerateRect,
    /// A segment's endpoints coincide.
    ZeroLengthSegment,
    /// More than one of the above, in the order of the constructor's
    /// arguments (never nested, never fewer than two).
    Several(Vec<LightError>),
}

impl LightError {
    /// Each fault, in the order of the constructor's arguments: this one,
    /// or the list of [`LightError::Several`].
    #[must_use]
    pub fn faults(&self) -> &[LightError] {
        match self {
            LightError::Several(all) => all,
            one => std::slice::from_ref(one),
        }
    }

    /// The faults found, as one error: `Ok` for none.
    pub(super) fn from_faults(mut faults: Vec<LightError>) -> Result<(), LightError> {
        match faults.len() {
            0 => Ok(()),
            1 => Err(faults.remove(0)),
            _ => Err(LightError::Several(faults)),
        }
    }
}

impl_error!(LightError, |error, f| match error {
    LightError::NonFinite { field } => write!(f, "light field `{field}` is not finite"),
    LightError::NonPositiveRadius { radius } => {
        write!(f, "light radius must be positive, got {radius}")
    }
    LightError::ZeroNormal => write!(f, "disk light normal is zero"),
    LightError::DegenerateRect => write!(f, "rect light half-axes span no area"),
    LightError::ZeroLengthSegment => write!(f, "segment light endpoints coincide"),
    LightError::Several(all) => {
        for (k, e) in all.iter().enumerate() {
            if k > 0 {
                f.write_str("; ")?;
            }
            write!(f, "{e}")?;
        }
        Ok(())
    }
});

/// Why a receiver cannot see a light's measure.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum ReceiverError {
    /// The receiver has a NaN or infinite coordinate.
    NonFinite,
    /// The receiver is inside (or on) a sphere light.
    InsideSphere,
    /// The receiver lies in the plane of a disk or rect light (to rounding):
    /// the light is seen edge-on and its visible fraction is undefined.
    InLightPlane,
    /// The receiver is at the point light's position, or on a segment
    /// light.
    OnLight,
    /// The scene around the receiver is beyond a reference's range: the
    /// exact reference's determinants (products of three coordinate
    /// differences) would overflow or the whole scene lies below `10⁻⁹⁰`
    /// (where they underflow), or, for Monte Carlo, a coordinate
    /// exceeds its segment test's domain (`10⁹⁰`). See the domains in the
    /// documentation of `reference::exact` and `reference::monte_carlo`.
    OutOfRange,
}

impl_error!(ReceiverError, |error, f| match error {
    ReceiverError::NonFinite => write!(f, "receiver position is not finite"),
    ReceiverError::InsideSphere => write!(f, "receiver is inside the sphere light"),
    ReceiverError::InLightPlane => write!(f, "receiver lies in the light's plane"),
    ReceiverError::OnLight => write!(f, "receiver lies on the light"),
    ReceiverError::OutOfRange => write!(
        f,
        "the scene's coordinates around the receiver are beyond the reference's range"
    ),
});

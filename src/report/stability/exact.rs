//! The exact reference's section: every family twice, dyadic (the
//! closed form exact, the moved scene the same scene) and in general
//! position with ordinary coordinates (every input rounded; the closed
//! form of the scene as rounded, [`General`]).

use super::general::General;
use super::measured::{exact_error, Measured};
use super::plate::{receivers, Plate};
use super::Row;
use crate::kernel::catalogue::Stiff;
use glam::DVec3;

/// The plate every family starts from: a light of radius ½ at height 2,
/// the plate at height 1, its edge over the light's centre.
const UNIT: Plate = Plate {
    r: 0.5,
    big_h: 2.0,
    h: 1.0,
    s: 0.0,
};

/// The exact reference's rows, family by family.
pub(super) fn rows(rows: &mut Vec<Row>) {
    far_offset(rows);
    light_size(rows);
    grazing(rows);
    contact(rows);
    coincident_edges(rows);
    deep_overlap(rows);
}

/// One row of `n` receivers measured as `m`.
fn exact_row(family: &'static str, case: String, m: Measured, n: usize) -> Row {
    Row {
        subject: "exact reference".to_owned(),
        family,
        case,
        precision: "f64",
        count: n - m.refused,
        max: m.max,
        bound: Some(m.bound),
        note: if m.violations > 0 {
            format!("{} bounds below their error", m.violations)
        } else if m.refused > 0 {
            format!(
                "{} receivers refused (a typed error, documented)",
                m.refused
            )
        } else if m.max <= 4e-15 {
            "inside; within a few ulps, every bound containing its error".to_owned()
        } else {
            "inside the documented domain, above a few ulps; every bound containing its error"
                .to_owned()
        },
    }
}

/// The rows of one case twice: `case, dyadic` as placed and `case,
/// ordinary` in general position (offsets of size 1), each over
/// `copies` plates each `shift` further ([`exact_error`]).
fn both_rows(
    rows: &mut Vec<Row>,
    family: Stiff,
    case: String,
    plate: &Plate,
    pts: &[DVec3],
    copies: usize,
    shift: f64,
) {
    rows.push(exact_row(
        family.name(),
        format!("{case}, dyadic"),
        exact_error(plate, DVec3::ZERO, pts, copies, shift),
        pts.len(),
    ));
    rows.push(exact_row(
        family.name(),
        format!("{case}, ordinary"),
        general(1.0).measure(plate, pts, copies, shift),
        pts.len(),
    ));
}

/// General position: turned by these angles, moved by ordinary offsets
/// of size `scale`.
fn general(scale: f64) -> General {
    General::new(
        0.7319,
        -0.4127,
        DVec3::new(0.61237, -0.44371, 0.77113) * scale,
    )
}

/// Far offsets: dyadic, so the moved scene is the same scene; and
/// ordinary offsets of the same size in general position.
fn far_offset(rows: &mut Vec<Row>) {
    let base = receivers(&UNIT, 0.0, 33);
    let base: Vec<DVec3> = base
        .iter()
        .map(|p| DVec3::new((p.x * 1024.0).round() / 1024.0, p.y, p.z))
        .collect();
    for e in [3, 4, 5, 6, 7, 8, 9] {
        let d = 2f64.powi((f64::from(e) * std::f64::consts::LOG2_10).round() as i32);
        let offset = DVec3::new(d, d * 0.5, -d);
        rows.push(exact_row(
            Stiff::FarOffset.name(),
            format!("10^{e} (2^{}), dyadic", d.log2() as i32),
            exact_error(&UNIT, offset, &base, 1, 0.0),
            base.len(),
        ));
        rows.push(exact_row(
            Stiff::FarOffset.name(),
            format!("10^{e}, ordinary"),
            general(10f64.powi(e)).measure(&UNIT, &base, 1, 0.0),
            base.len(),
        ));
    }
}

/// Light size relative to its height.
fn light_size(rows: &mut Vec<Row>) {
    for r in [1e-6, 1e-5, 1e-4, 1e-3, 10.0, 100.0, 1000.0] {
        let plate = Plate { r, ..UNIT };
        let pts = receivers(&plate, 0.0, 33);
        both_rows(
            rows,
            Stiff::LightSize,
            format!("r = {r:e}"),
            &plate,
            &pts,
            1,
            0.0,
        );
    }
}

/// Grazing: the receivers far to the side, seeing the light at
/// elevation θ.
fn grazing(rows: &mut Vec<Row>) {
    for e in [1, 2, 3, 4, 5, 6] {
        let theta = 10f64.powi(-e);
        let x = -UNIT.big_h / theta;
        // The edge where the penumbra's middle falls at x: c = 0.
        let k = UNIT.big_h / UNIT.h;
        // Dyadic (multiples of 2^-28), so that the closed form's
        // `c = x + (s − x)·2` is exact and its error is not the answer's.
        let dyadic = |v: f64| (v * 268_435_456.0).round() / 268_435_456.0;
        let plate = Plate {
            s: dyadic(x * (k - 1.0) / k),
            ..UNIT
        };
        let pts: Vec<DVec3> = (0..33)
            .map(|i| {
                let t = -0.95 + 1.9 * f64::from(i) / 32.0;
                DVec3::new(dyadic((t * plate.r - plate.s * k) / (1.0 - k)), 0.0, 0.0)
            })
            .collect();
        both_rows(
            rows,
            Stiff::Grazing,
            format!("elevation 1e-{e}"),
            &plate,
            &pts,
            1,
            0.0,
        );
    }
}

/// Contact: the receivers just under the plate.
fn contact(rows: &mut Vec<Row>) {
    for e in [10, 20, 30] {
        let y = UNIT.h - 2f64.powi(-e);
        let pts = receivers(&UNIT, y, 33);
        rows.push(exact_row(
            Stiff::Contact.name(),
            format!("2^-{e} under the plate, dyadic"),
            exact_error(&UNIT, DVec3::ZERO, &pts, 1, 0.0),
            pts.len(),
        ));
    }
    for e in [3, 6, 9, 12] {
        let y = UNIT.h - 1.37 * 10f64.powi(-e);
        let pts = receivers(&UNIT, y, 33);
        rows.push(exact_row(
            Stiff::Contact.name(),
            format!("1.37e-{e} under the plate, ordinary"),
            general(1.0).measure(&UNIT, &pts, 1, 0.0),
            pts.len(),
        ));
    }
}

/// Nearly coincident edges: a second plate's edge 2^-k past the first.
fn coincident_edges(rows: &mut Vec<Row>) {
    for e in [20, 40, 52] {
        let pts = receivers(&UNIT, 0.0, 33);
        both_rows(
            rows,
            Stiff::CoincidentEdges,
            format!("second edge 2^-{e} away"),
            &UNIT,
            &pts,
            2,
            2f64.powi(-e),
        );
    }
}

/// Deep overlap: 10⁴ plates on one another (the same, then each 2^-30
/// further; the union is the first).
fn deep_overlap(rows: &mut Vec<Row>) {
    let pts = receivers(&UNIT, 0.0, 9);
    for (case, shift) in [
        ("10^4 coincident plates", 0.0),
        ("10^4 plates, each 2^-30 further", 2f64.powi(-30)),
    ] {
        both_rows(
            rows,
            Stiff::DeepOverlap,
            case.to_owned(),
            &UNIT,
            &pts,
            10_000,
            shift,
        );
    }
}

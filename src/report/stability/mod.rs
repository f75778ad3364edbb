//! The stability suite (`softshadow stability`): the kernels in `f32`
//! against `f64`, the exact reference against closed forms, and every
//! method of the default sets on stiff scenes, over families of extreme
//! input — far offsets, tiny and huge lights, grazing views, contact,
//! nearly coincident edges, deep overlap.
//!
//! # The answers measured against
//!
//! - **The exact reference** (`f64`): one straight edge of a plate parallel
//!   to a disk light hides, from a receiver, the part of the disk beyond a
//!   line — a circle segment, whose area has a closed form. Every family
//!   is built on that configuration; where it is moved far from the origin
//!   the coordinates are dyadic with few bits, so that the moved scene is
//!   the same scene exactly and the closed form does not change.
//! - **`f32` kernels**: the `f64` kernel on the same (`f32`-rounded)
//!   input, so that the error is the `f32` arithmetic's and not the
//!   input's rounding.
//! - **`f64` kernels**: answers known independently — a circle segment's
//!   area from its half-angle (a series for thin segments), the falloff's
//!   exact symmetry and thin-sliver closed form, the Bernstein polynomial
//!   where it is exact, silhouettes against a facing test per face. Their
//!   errors against 256-bit evaluations on random stiff input are measured
//!   by the tests (`docs/accuracy/kernels.md`).
//! - **Methods**: the exact reference on the same stiff scene, and the
//!   method's own answer on the scene before it was moved.
//!
//! The kernels measured, the stiff families each is measured on and the
//! bounds the notes quote are those of the kernel catalogue
//! ([`crate::kernel::catalogue`]); a unit test holds the kernel rows to it.

//!
//! # Layout
//!
//! | file | what |
//! |---|---|
//! | `plate.rs` | the closed-form case: a disk light over a plate's straight edge; receivers across its penumbra; a circle segment's area |
//! | `measured.rs` | the exact reference's worst error and bounds against a closed form; the dyadic far scenes |
//! | `general.rs`, `dd.rs` | the same cases in general position, their closed form in double-double |
//! | `exact.rs` | the exact reference's rows, family by family |
//! | `kernels_f32.rs` | the `f32` kernels against `f64` |
//! | `kernels_f64.rs`, `wedge.rs`, `silhouette.rs` | the `f64` kernels against independent answers |
//! | `methods.rs` | the methods on stiff scenes |

mod dd;
mod exact;
mod general;
mod kernels_f32;
mod kernels_f64;
mod measured;
mod methods;
mod plate;
mod silhouette;
mod wedge;

use crate::kernel::catalogue::Stiff;
use std::fmt::Write as _;

/// One measured row.
#[derive(Clone, Debug)]
pub struct Row {
    /// What is measured (`exact reference`, `disk::segment_disk_area`, a
    /// method's name).
    pub subject: String,
    /// The family (`far offset`, …).
    pub family: &'static str,
    /// The family's parameter for this row.
    pub case: String,
    /// `f32` or `f64`.
    pub precision: &'static str,
    /// Inputs evaluated.
    pub count: usize,
    /// The largest error (in the unit the section states).
    pub max: f64,
    /// For the exact reference, the largest of its certified bounds over
    /// the row's receivers (and whether each contained its error: the
    /// note says otherwise).
    pub bound: Option<f64>,
    /// Whether the row is inside the subject's documented domain, and if
    /// not, why.
    pub note: String,
}

impl Row {
    /// A row of a subject without a certified bound.
    fn new(
        precision: &'static str,
        subject: &str,
        family: &'static str,
        case: impl Into<String>,
        count: usize,
        max: f64,
        note: impl Into<String>,
    ) -> Row {
        Row {
            subject: subject.to_owned(),
            family,
            case: case.into(),
            precision,
            count,
            max,
            bound: None,
            note: note.into(),
        }
    }

    /// A row of `precision` and `subject` for each case `(family, case,
    /// (count, largest error), note)`, in order.
    fn push_cases<N: Into<String>>(
        rows: &mut Vec<Row>,
        precision: &'static str,
        subject: &str,
        cases: impl IntoIterator<Item = (Stiff, String, (usize, f64), N)>,
    ) {
        for (family, case, (count, max), note) in cases {
            rows.push(Row::new(
                precision,
                subject,
                family.name(),
                case,
                count,
                max,
                note,
            ));
        }
    }
}

/// Runs the suite: the exact reference, the kernels, the methods at
/// `side²`.
#[must_use]
pub fn run(side: u32, progress: &dyn Fn(&str)) -> Vec<Row> {
    let mut rows = Vec::new();
    progress("the exact reference");
    exact::rows(&mut rows);
    kernel_rows(&mut rows, progress);
    progress("the methods on stiff scenes");
    methods::rows(&mut rows, side);
    rows
}

/// The kernels' rows: `f32` against `f64`, then `f64` against
/// independent answers.
fn kernel_rows(rows: &mut Vec<Row>, progress: &dyn Fn(&str)) {
    progress("the kernels in f32");
    kernels_f32::rows(rows);
    progress("the kernels in f64");
    kernels_f64::polygon_disk_area_rows(rows);
    kernels_f64::falloff_rows(rows);
    wedge::rows(rows);
    silhouette::rows(rows);
}

/// `docs/stability.md` from the rows.
#[must_use]
pub fn markdown(rows: &[Row], machine: &str, command: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Stability on stiff and extreme input\n");
    let _ = writeln!(
        s,
        "Written by `{command}` ({machine}). Three parts: the exact reference against closed \
         forms, the kernels (`f32` against `f64`, `f64` against closed forms), and every method of the default set on \
         stiff versions of the default scene. Rows outside a subject's documented domain say so \
         in the last column rather than being left out.\n"
    );
    type Keep<'a> = &'a dyn Fn(&Row) -> bool;
    let sections: [(&str, Keep<'_>, &str); 3] = [
        (
            "The exact reference against closed forms",
            &|r: &Row| r.subject == "exact reference",
            "A disk light over a plate parallel to it: the plate's straight edge hides a circle \
             segment of the light, whose area is a closed form (the error of the closed form \
             itself is a few `ε`). Every family twice: *dyadic* — axis-aligned, far offsets by a \
             power of two with dyadic coordinates, so the moved scene is exactly the same scene; \
             and *ordinary* — the same configuration turned by an ordinary rotation and moved by \
             an ordinary offset, every input coordinate rounded, the closed form evaluated for the \
             scene as rounded (the edge's trace on the light's plane in double-double). \"max\" \
             is the largest `|V − V_closed|`; \"bound\" the largest certified bound the exact \
             reference gave with its answers (`exact::visibility_bounded`), each of which must \
             contain its error (the note says if one did not).",
        ),
        (
            "The kernels",
            &|r: &Row| r.subject.contains("::"),
            "`f32` rows: each `f32` kernel against the `f64` kernel on the same `f32` input, so \
             that the error is the `f32` arithmetic's. `f64` rows: the `f64` kernels against \
             answers known independently — a circle segment's area from its half-angle (a series \
             for thin segments, so the closed form itself does not cancel), the falloff's exact \
             symmetry and its thin-sliver closed form, the Bernstein polynomial at points where \
             it is exact in `f64`, and silhouettes against a facing test per face. The `f64` \
             kernels against 256-bit evaluations on random stiff input: \
             `docs/accuracy/kernels.md` (the tests).",
        ),
        (
            "The methods on stiff scenes",
            &|r: &Row| r.subject != "exact reference" && !r.subject.contains("::"),
            "Each method of the sphere light's default set on the default scene moved far from \
             the origin (its coordinates round there, so the moved scene differs from the built-in \
             one by that rounding), with a tiny and a huge light, with the light near the horizon, \
             and on `contact`. \"max\" is the RMSE against the exact reference on the same \
             scene; the note gives the method's RMSE on the default scene as built in.",
        ),
    ];
    for (title, keep, text) in sections {
        let _ = writeln!(s, "## {title}\n\n{text}\n");
        let bounded = rows.iter().filter(|r| keep(r)).any(|r| r.bound.is_some());
        if bounded {
            let _ = writeln!(
                s,
                "| subject | family | case | precision | inputs | max | bound | domain / note |"
            );
            let _ = writeln!(s, "|---|---|---|---|---:|---:|---:|---|");
        } else {
            let _ = writeln!(
                s,
                "| subject | family | case | precision | inputs | max | domain / note |"
            );
            let _ = writeln!(s, "|---|---|---|---|---:|---:|---|");
        }
        for r in rows.iter().filter(|r| keep(r)) {
            let bound = match (bounded, r.bound) {
                (false, _) => String::new(),
                (true, Some(b)) => format!(" {b:.2e} |"),
                (true, None) => " — |".to_owned(),
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {:.2e} |{bound} {} |",
                r.subject, r.family, r.case, r.precision, r.count, r.max, r.note
            );
        }
        let _ = writeln!(s);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::{kernel_rows, Row};
    use crate::kernel::catalogue::FAMILIES;
    use std::collections::BTreeSet;

    /// The kernels' rows measure each family of the kernel catalogue on
    /// exactly the stiff cases the catalogue lists for it, and name no
    /// kernel the catalogue does not.
    #[test]
    fn the_kernel_rows_follow_the_catalogue() {
        let mut rows = Vec::new();
        kernel_rows(&mut rows, &|_| {});
        let family_of = |r: &Row| r.subject.split("::").next().unwrap_or("").to_owned();
        for r in &rows {
            let name = family_of(r);
            assert!(
                FAMILIES.iter().any(|f| f.name == name),
                "{}: not in the catalogue",
                r.subject
            );
        }
        for f in FAMILIES {
            let measured: BTreeSet<&str> = rows
                .iter()
                .filter(|r| family_of(r) == f.name)
                .map(|r| r.family)
                .collect();
            let listed: BTreeSet<&str> = f.stiff.iter().map(|s| s.name()).collect();
            assert_eq!(measured, listed, "{}", f.name);
        }
    }
}

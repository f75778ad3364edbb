//! Scoring an image of `V` made elsewhere against the exact answer on the
//! same receivers, with the statistics of the report's error table
//! ([error statistics](crate::definitions#error-statistics) over the
//! [receiver groups](crate::definitions#receiver-groups), for `V` and for
//! the shaded value `V·max(0, n·l̂)`).
//!
//! The receiver groups, the shading factors and the per-group
//! [`ErrorSummary`]s here are the ones the report uses
//! ([`group_masks`], [`shading_factors`], [`group_errors`]), so a score and
//! a report row of the same values are the same numbers.
//!
//! An image pixel whose value is NaN or infinite at a surface pixel is
//! counted ([`Score::nan_pixels`]) and left out of the statistics — never
//! silently: [`Score::passes`] fails any image with one. Values at
//! background pixels are ignored.

use super::image::ErrorSummary;
use crate::bvh::Bvh;
use crate::definitions::in_penumbra;
use crate::kernel::receiver_view::Pieces;
use crate::method::{self, Exact, MethodError};
use crate::reference::exact;
use crate::render::frame::{Frame, BACKGROUND};
use crate::render::stages::Stages;
use crate::scene::{Light, LightKind, Receiver, Scene};
use std::fmt::Write as _;

/// The receiver groups, in table order: every receiver, the exact
/// penumbra ([`in_penumbra`]), the ground (object 0) and the occluders
/// (every other object).
pub const GROUPS: [&str; 4] = ["all", "penumbra", "ground", "occluders"];

/// Per receiver, whether it is in each of [`GROUPS`], from the exact
/// values (one per receiver). A receiver without an object id is in
/// neither the ground nor the occluders.
#[must_use]
pub fn group_masks(receivers: &[Receiver], exact: &[f64]) -> [Vec<bool>; 4] {
    [
        vec![true; receivers.len()],
        (0..receivers.len())
            .map(|i| exact.get(i).is_some_and(|&v| in_penumbra(v)))
            .collect(),
        receivers.iter().map(|r| r.object == Some(0)).collect(),
        receivers
            .iter()
            .map(|r| r.object.is_some_and(|o| o != 0))
            .collect(),
    ]
}

/// The groups of a segment light's receivers by the visible pieces of the
/// light, in table order ([`Pieces::ALL`]): one piece holding an end (the
/// case occluding edges soft shadows models), one piece inside the light,
/// two or more pieces, none (umbra), the whole light.
pub const PIECES: [&str; 5] = [
    "one piece at an end",
    "one piece inside",
    "two or more pieces",
    "no piece (umbra)",
    "the whole light",
];

/// Per receiver, whether it is in each of [`PIECES`], when the light is a
/// segment (`None` for any other light): how the exact reference sees
/// the light from it ([`exact::pieces_many`]). Each receiver is in one
/// group, but a receiver the exact reference refuses (on the light, not
/// finite), which is in none.
#[must_use]
pub fn pieces_masks(bvh: &Bvh, light: &Light, receivers: &[Receiver]) -> Option<[Vec<bool>; 5]> {
    if light.kind() != LightKind::Segment {
        return None;
    }
    let points: Vec<_> = receivers.iter().map(|r| r.position).collect();
    let seen = exact::pieces_many(bvh, light, &points);
    Some(Pieces::ALL.map(|kind| {
        seen.iter()
            .map(|s| matches!(s, Ok(Some(k)) if *k == kind))
            .collect()
    }))
}

/// Per receiver, the factor `max(0, n·l̂)` of the shaded value (`l̂` toward
/// the light's centre; 1 for a receiver without a normal).
#[must_use]
pub fn shading_factors(light: &Light, receivers: &[Receiver]) -> Vec<f64> {
    receivers
        .iter()
        .map(|r| {
            let l = (light.center() - r.position).normalize_or_zero();
            r.normal.map_or(1.0, |n| n.dot(l).max(0.0))
        })
        .collect()
}

/// The [`ErrorSummary`] of `values` against `reference` over each group of
/// `masks` ([`group_masks`], [`pieces_masks`]), restricted to the indices
/// where `keep`.
#[must_use]
pub fn group_errors<const N: usize>(
    values: &[f64],
    reference: &[f64],
    masks: &[Vec<bool>; N],
    keep: impl Fn(usize) -> bool,
) -> [ErrorSummary; N] {
    masks.each_ref().map(|m| {
        ErrorSummary::new(values, reference, |i| {
            m.get(i).copied().unwrap_or(false) && keep(i)
        })
    })
}

/// The shaded values: `x` times the per-receiver `factors`
/// ([`shading_factors`]).
#[must_use]
pub fn scaled(x: &[f64], factors: &[f64]) -> Vec<f64> {
    x.iter().zip(factors).map(|(v, s)| v * s).collect()
}

/// The errors of `values` (one per receiver) against `exact` over the
/// groups, for `V` and for the shaded value: the report's two rows of
/// group summaries.
#[must_use]
pub fn errors_of(
    light: &Light,
    receivers: &[Receiver],
    values: &[f64],
    exact: &[f64],
    keep: impl Fn(usize) -> bool + Copy,
) -> ([ErrorSummary; 4], [ErrorSummary; 4]) {
    let masks = group_masks(receivers, exact);
    let factors = shading_factors(light, receivers);
    let v = group_errors(values, exact, &masks, keep);
    let shaded = group_errors(
        &scaled(values, &factors),
        &scaled(exact, &factors),
        &masks,
        keep,
    );
    (v, shaded)
}

/// The Monte Carlo sample count of equal RMSE for a score, measured on the
/// same receivers (or a seeded random subset of them): see `mc_equal`
/// (feature `report`).
#[derive(Clone, Debug, PartialEq)]
pub struct McEqual {
    /// The fitted `N`, where within the measured range.
    pub n: Option<f64>,
    /// As the report writes it: `412`, `< 2`, `> 4096`.
    pub text: String,
    /// The receivers measured (the subset).
    pub receivers: usize,
    /// Of how many scored.
    pub of: usize,
    /// The image's RMSE over the subset (the number matched).
    pub rmse: f64,
    /// The seed of the subset and of Monte Carlo's samples.
    pub seed: u64,
    /// With a subset: the 2.5 and 97.5 percentiles of the fitted `N` over
    /// bootstrap resamples of the subset's receivers (`n` and the bounds of
    /// the measured range standing for values outside it).
    pub interval: Option<(f64, f64)>,
    /// The sample counts measured.
    pub counts: Vec<u32>,
    /// Monte Carlo's RMSE at each count, on the subset.
    pub mc_rmse: Vec<f64>,
    /// Monte Carlo's seconds at each count, on the subset.
    pub mc_seconds: Vec<f64>,
}

/// An image of `V` scored against the exact answer.
#[derive(Clone, Debug, PartialEq)]
pub struct Score {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Pixels that see a surface (receivers).
    pub surface_pixels: usize,
    /// Surface pixels whose value is finite: those scored.
    pub pixels: usize,
    /// Surface pixels whose value is NaN or infinite: counted, not scored.
    pub nan_pixels: usize,
    /// The first of them, `(row, col)`.
    pub first_nan: Option<(u32, u32)>,
    /// Errors of `V` per group ([`GROUPS`] order).
    pub v: [ErrorSummary; 4],
    /// Errors of the shaded value `V·max(0, n·l̂)` per group.
    pub shaded: [ErrorSummary; 4],
    /// The Monte Carlo sample count of equal RMSE, when measured.
    pub mc_equal: Option<McEqual>,
}

/// A [`Score`] with the exact values it was measured against.
#[derive(Clone, Debug, PartialEq)]
pub struct Scored {
    /// The statistics.
    pub score: Score,
    /// The exact `V`, one per receiver of the frame.
    pub exact: Vec<f64>,
    /// The image's values, one per receiver of the frame (NaN kept).
    pub values: Vec<f64>,
}

impl Score {
    /// The score of `image` (`width · height` values of the frame's size,
    /// row-major from the top-left) against `exact` (one per receiver of
    /// `frame`), with the shading of `light`.
    ///
    /// Returns the score and the image's value per receiver.
    #[must_use]
    pub fn new(frame: &Frame, light: &Light, image: &[f64], exact: &[f64]) -> (Score, Vec<f64>) {
        let (width, height) = frame.size();
        let receivers = frame.receivers();
        let mut values = vec![f64::NAN; receivers.len()];
        let mut first_nan = None;
        for (k, &i) in frame.pixels().iter().enumerate() {
            if i == BACKGROUND {
                continue;
            }
            let v = image.get(k).copied().unwrap_or(f64::NAN);
            if !v.is_finite() && first_nan.is_none() {
                first_nan = Some(((k / width as usize) as u32, (k % width as usize) as u32));
            }
            if let Some(slot) = values.get_mut(i as usize) {
                *slot = v;
            }
        }
        let finite = |i: usize| values[i].is_finite();
        let (v, shaded) = errors_of(light, receivers, &values, exact, finite);
        let pixels = values.iter().filter(|v| v.is_finite()).count();
        let score = Score {
            width,
            height,
            surface_pixels: receivers.len(),
            pixels,
            nan_pixels: receivers.len() - pixels,
            first_nan,
            v,
            shaded,
            mc_equal: None,
        };
        (score, values)
    }

    /// RMSE of `V` over every scored receiver.
    #[must_use]
    pub fn rmse(&self) -> f64 {
        self.v[0].rmse
    }

    /// Whether the image passes a gate at `max_rmse`: no NaN or infinite
    /// surface pixel, and RMSE at most `max_rmse`.
    #[must_use]
    pub fn passes(&self, max_rmse: f64) -> bool {
        self.nan_pixels == 0 && self.rmse() <= max_rmse
    }

    /// The headline statistics, by the names of `score --json`:
    /// `pixels`, `nan_pixels`, `surface_pixels`, `rmse`, `rmse_penumbra`,
    /// `rmse_ground`, `rmse_occluders`, `rmse_shaded`, `mean_abs`,
    /// `mean_signed`, `max_abs`, `p99_abs`, `share_over_0_05`,
    /// `penumbra_pixels`, `ground_pixels`, `occluder_pixels`.
    #[must_use]
    pub fn fields(&self) -> Vec<(&'static str, f64)> {
        let [all, pen, ground, occ] = self.v;
        vec![
            ("pixels", self.pixels as f64),
            ("nan_pixels", self.nan_pixels as f64),
            ("surface_pixels", self.surface_pixels as f64),
            ("rmse", all.rmse),
            ("rmse_penumbra", pen.rmse),
            ("rmse_ground", ground.rmse),
            ("rmse_occluders", occ.rmse),
            ("rmse_shaded", self.shaded[0].rmse),
            ("mean_abs", all.mean_abs),
            ("mean_signed", all.mean_signed),
            ("max_abs", all.max_abs),
            ("p99_abs", all.p99_abs),
            ("share_over_0_05", all.share_over_0_05),
            ("penumbra_pixels", pen.count as f64),
            ("ground_pixels", ground.count as f64),
            ("occluder_pixels", occ.count as f64),
        ]
    }

    /// One JSON object: `width`, `height`, the [`Score::fields`] (counts as
    /// integers), `first_nan` (`[row, col]` or null), `groups` and
    /// `shaded` (per group of [`GROUPS`], every [`ErrorSummary`] field),
    /// and with a yardstick `mc_equal_n` (a number, or null outside the
    /// measured range), `mc_equal` (the report's text), `mc_equal_interval`
    /// (`[lo, hi]` or null), `mc_receivers`, `mc_of`, `mc_seed`,
    /// `mc_counts`, `mc_rmse`, `mc_seconds`. Non-finite numbers are null.
    #[must_use]
    pub fn to_json(&self) -> String {
        let mut s = format!("{{\"width\": {}, \"height\": {}", self.width, self.height);
        for (name, value) in self.fields() {
            let text = if name.ends_with("pixels") {
                format!("{}", value as u64)
            } else {
                num(value)
            };
            let _ = write!(s, ", \"{name}\": {text}");
        }
        let _ = write!(
            s,
            ", \"first_nan\": {}",
            self.first_nan
                .map_or("null".to_owned(), |(r, c)| format!("[{r}, {c}]"))
        );
        for (key, groups) in [("groups", &self.v), ("shaded", &self.shaded)] {
            let _ = write!(s, ", \"{key}\": {{");
            for (k, (name, e)) in GROUPS.iter().zip(groups).enumerate() {
                let _ = write!(
                    s,
                    "{}\"{name}\": {{\"count\": {}, \"mean_abs\": {}, \"rmse\": {}, \"p99_abs\": {}, \"max_abs\": {}, \"mean_signed\": {}, \"share_over_0_05\": {}}}",
                    if k == 0 { "" } else { ", " },
                    e.count,
                    num(e.mean_abs),
                    num(e.rmse),
                    num(e.p99_abs),
                    num(e.max_abs),
                    num(e.mean_signed),
                    num(e.share_over_0_05)
                );
            }
            s.push('}');
        }
        if let Some(m) = &self.mc_equal {
            let list = |x: &[f64]| x.iter().map(|v| num(*v)).collect::<Vec<_>>().join(", ");
            let _ = write!(
                s,
                ", \"mc_equal_n\": {}, \"mc_equal\": \"{}\", \"mc_equal_interval\": {}, \"mc_receivers\": {}, \"mc_of\": {}, \"mc_seed\": {}, \"mc_rmse_subset\": {}, \"mc_counts\": [{}], \"mc_rmse\": [{}], \"mc_seconds\": [{}]",
                m.n.map_or("null".to_owned(), num),
                m.text,
                m.interval
                    .map_or("null".to_owned(), |(a, b)| format!("[{}, {}]", num(a), num(b))),
                m.receivers,
                m.of,
                m.seed,
                num(m.rmse),
                m.counts.iter().map(u32::to_string).collect::<Vec<_>>().join(", "),
                list(&m.mc_rmse),
                list(&m.mc_seconds),
            );
        }
        s.push('}');
        s
    }

    /// The error table, as the report's per-group tables: a Markdown
    /// header and one row per group, for `V` then for the shaded value.
    #[must_use]
    pub fn table(&self) -> String {
        let mut s = String::from(
            "| value | receivers | count | mean abs | RMSE | p99 abs | max | mean signed | share > 0.05 |\n\
             |---|---|---:|---:|---:|---:|---:|---:|---:|\n",
        );
        for (value, groups) in [("V", &self.v), ("shaded", &self.shaded)] {
            for (name, e) in GROUPS.iter().zip(groups) {
                let _ = writeln!(
                    s,
                    "| {value} | {name} | {} | {:.5} | {:.5} | {:.4} | {:.4} | {:+.5} | {:.4} |",
                    e.count,
                    e.mean_abs,
                    e.rmse,
                    e.p99_abs,
                    e.max_abs,
                    e.mean_signed,
                    e.share_over_0_05
                );
            }
        }
        s
    }
}

/// A JSON number (the shortest text that reads back to the same `f64`),
/// or `null` when not finite.
fn num(x: f64) -> String {
    if x.is_finite() {
        format!("{x:?}")
    } else {
        "null".to_owned()
    }
}

/// Scores `image` (the frame's size, row-major from the top-left) on the
/// receivers of `frame`: computes the exact `V` at each receiver
/// ([`Exact`](struct@Exact)) and the [`Score`].
///
/// # Errors
/// A receiver the light cannot be seen from ([`MethodError::Receiver`],
/// by receiver index).
pub fn score(scene: &Scene, frame: &Frame, image: &[f64]) -> Result<Scored, MethodError> {
    let stages = Stages::new(scene);
    let exact = method::run(&Exact, &stages, frame)?.output.visibility;
    let (score, values) = Score::new(frame, scene.light(), image, &exact);
    Ok(Scored {
        score,
        exact,
        values,
    })
}

/// How [`mc_equal`] measures.
#[cfg(feature = "report")]
#[derive(Clone, Debug, PartialEq)]
pub struct McOptions {
    /// Monte Carlo's sample counts (default the report's, 2 … 4096).
    pub counts: Vec<u32>,
    /// At most this many receivers, a seeded random subset when there are
    /// more (default 16384).
    pub receivers: usize,
    /// The subset's and the samples' seed.
    pub seed: u64,
    /// Bootstrap resamples for the interval (default 200).
    pub resamples: usize,
}

#[cfg(feature = "report")]
impl Default for McOptions {
    fn default() -> McOptions {
        McOptions {
            counts: super::yardstick::default_mc(),
            receivers: 16384,
            seed: 1,
            resamples: 200,
        }
    }
}

/// `splitmix64`: the subset's and the bootstrap's random stream.
#[cfg(feature = "report")]
fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The report's yardstick for a score: Monte Carlo at each of
/// `options.counts` samples on the scored receivers (a seeded random subset
/// of `options.receivers` of them when there are more), its RMSE against
/// `N` fitted by the report's power law, and the `N` at which it meets the
/// image's RMSE on the same receivers ([`Yardstick`](super::yardstick::Yardstick)). With a
/// subset, the interval of the fitted `N` over bootstrap resamples of the
/// subset's receivers states its uncertainty.
///
/// # Errors
/// Monte Carlo's (a receiver the light cannot be seen from).
#[cfg(feature = "report")]
pub fn mc_equal(
    scene: &Scene,
    frame: &Frame,
    scored: &Scored,
    options: &McOptions,
) -> Result<McEqual, MethodError> {
    use super::yardstick::{Equal, Yardstick};
    use crate::method::MonteCarlo;
    let scored_ix: Vec<usize> = (0..scored.values.len())
        .filter(|&i| scored.values[i].is_finite())
        .collect();
    let of = scored_ix.len();
    let mut state = options.seed;
    let mut subset = scored_ix;
    let sampled = subset.len() > options.receivers;
    if sampled {
        // A partial Fisher–Yates shuffle, then receiver order.
        for k in 0..options.receivers {
            let j = k + (splitmix(&mut state) % (subset.len() - k) as u64) as usize;
            subset.swap(k, j);
        }
        subset.truncate(options.receivers);
        subset.sort_unstable();
    }
    let receivers: Vec<Receiver> = subset.iter().map(|&i| frame.receivers()[i]).collect();
    let exact: Vec<f64> = subset.iter().map(|&i| scored.exact[i]).collect();
    let image: Vec<f64> = subset.iter().map(|&i| scored.values[i]).collect();
    let masks = group_masks(&receivers, &exact);
    let sub = Frame::from_receivers(receivers);
    let stages = Stages::new(scene);
    stages.bvh();
    let mut runs = Vec::new();
    for &n in &options.counts {
        let mc = MonteCarlo::new(n).with_seed(options.seed);
        let run = method::run(&mc, &stages, &sub)?;
        runs.push((n, run.output.visibility, run.seconds));
    }
    // RMSE over the receivers `pick` (indices into the subset, repeats
    // allowed).
    let rmse = |v: &[f64], pick: &[usize]| -> f64 {
        let s: f64 = pick.iter().map(|&i| (v[i] - exact[i]).powi(2)).sum();
        (s / pick.len().max(1) as f64).sqrt()
    };
    let fit = |pick: &[usize]| -> Option<(Equal, f64, Vec<f64>)> {
        let pen: Vec<usize> = pick.iter().copied().filter(|&i| masks[1][i]).collect();
        let points: Vec<(u32, f64, f64, f64)> = runs
            .iter()
            .map(|(n, v, t)| (*n, rmse(v, pick), rmse(v, &pen), *t))
            .collect();
        let y = Yardstick::new(&points)?;
        let r = rmse(&image, pick);
        Some((
            y.equal(&y.rmse, r)?,
            r,
            points.iter().map(|p| p.1).collect(),
        ))
    };
    let all: Vec<usize> = (0..exact.len()).collect();
    let (equal, image_rmse, mc_rmse) =
        fit(&all).unwrap_or((Equal::Below(0), rmse(&image, &all), Vec::new()));
    let (lo, hi) = (
        f64::from(options.counts.iter().copied().min().unwrap_or(0)),
        f64::from(options.counts.iter().copied().max().unwrap_or(0)),
    );
    let as_n = |e: Equal| match e {
        Equal::At(n) => n,
        Equal::Below(_) => lo,
        Equal::Above(_) => hi,
    };
    let interval = (sampled && !all.is_empty()).then(|| {
        let mut ns: Vec<f64> = (0..options.resamples)
            .filter_map(|_| {
                let pick: Vec<usize> = (0..all.len())
                    .map(|_| (splitmix(&mut state) % all.len() as u64) as usize)
                    .collect();
                fit(&pick).map(|f| as_n(f.0))
            })
            .collect();
        ns.sort_by(f64::total_cmp);
        let at = |q: f64| ns[((q * ns.len() as f64) as usize).min(ns.len().saturating_sub(1))];
        if ns.is_empty() {
            (f64::NAN, f64::NAN)
        } else {
            (at(0.025), at(0.975))
        }
    });
    Ok(McEqual {
        n: match equal {
            Equal::At(n) => Some(n),
            _ => None,
        },
        text: equal.to_string(),
        receivers: exact.len(),
        of,
        rmse: image_rmse,
        seed: options.seed,
        interval: interval.filter(|(a, b)| a.is_finite() && b.is_finite()),
        counts: options.counts.clone(),
        mc_rmse,
        mc_seconds: runs.iter().map(|r| r.2).collect(),
    })
}

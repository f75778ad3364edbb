//! The report's SVG plots, drawn with `plotters`: error against time per
//! scene and receiver group (log–log, every method setting a point, Monte
//! Carlo a curve, the Pareto front marked), and the falloff profile across
//! one penumbra per scene.

use super::{CellRecord, ConfigRecord, SceneRecord, GROUPS};
use plotters::coord::combinators::LogCoord;
use plotters::coord::{CoordTranslate, Shift};
use plotters::prelude::*;

/// One colour per method (base name), by its place in the registry.
fn colour(base: &str) -> RGBColor {
    const PALETTE: [RGBColor; 9] = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(127, 127, 127),
        RGBColor(23, 190, 207),
    ];
    let k = crate::method::registry::REGISTRY
        .iter()
        .position(|e| e.name == base)
        .unwrap_or(0);
    PALETTE[k % PALETTE.len()]
}

/// The frame of a chart on `root`, filled white first: `caption` above,
/// the margin and x label area of every plot of the report, `y_labels`
/// pixels for the y axis's labels.
fn framed<'a, 'b>(
    root: &'a DrawingArea<SVGBackend<'b>, Shift>,
    caption: String,
    y_labels: u32,
) -> Option<ChartBuilder<'a, 'b, SVGBackend<'b>>> {
    root.fill(&WHITE).ok()?;
    let mut builder = ChartBuilder::on(root);
    builder
        .caption(caption, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(y_labels);
    Some(builder)
}

/// The legend of `chart`'s labelled series at `position`, on a
/// translucent white box.
fn legend<'a, 'b: 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, SVGBackend<'b>, CT>,
    position: SeriesLabelPosition,
) -> Option<()> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()
        .ok()
}

/// A tick label: three significant digits, no trailing zeros.
fn short(v: f64) -> String {
    let s = format!("{v:.3e}");
    match s.parse::<f64>() {
        Ok(x) if (1e-3..1e5).contains(&x.abs()) => {
            let t = format!("{x:.6}");
            t.trim_end_matches('0').trim_end_matches('.').to_owned()
        }
        _ => s,
    }
}

/// The points `(ms, rmse)` not dominated by another (lower or equal in
/// both, lower in one), by increasing time: by time then error, each
/// point kept when its error is below every earlier one's (n log n).
fn pareto(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    sorted.dedup();
    let mut front: Vec<(f64, f64)> = Vec::new();
    for p in sorted {
        if front.last().is_none_or(|last| p.1 < last.1) {
            front.push(p);
        }
    }
    front
}

/// A label's box in pixels: left, top, right, bottom.
type LabelBox = (i32, i32, i32, i32);

fn overlaps(a: LabelBox, b: LabelBox) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}

/// Pixel size of `text` in the labels' font (sans-serif 11 px): a
/// generous estimate, so that estimated boxes that do not overlap are
/// drawn apart.
fn label_size(text: &str) -> (i32, i32) {
    (text.chars().count() as i32 * 6 + 2, 13)
}

/// Where to put a label of `size` for the point at `p` (pixels): the first
/// of a ring of places around it, ever farther, that stays inside `area`
/// and meets none of `taken`; `None` when all are taken. Returns the box.
fn place_label(
    p: (i32, i32),
    size: (i32, i32),
    area: LabelBox,
    taken: &[LabelBox],
) -> Option<LabelBox> {
    const ANGLES: [f64; 12] = [
        0.0, 180.0, -25.0, 25.0, 155.0, 205.0, -60.0, 60.0, 120.0, 240.0, -90.0, 90.0,
    ];
    for r in [7.0, 16.0, 28.0, 42.0, 60.0, 82.0, 108.0, 140.0, 180.0] {
        for a in ANGLES {
            let (dx, dy) = (r * f64::to_radians(a).cos(), -r * f64::to_radians(a).sin());
            let (x, y) = (p.0 + dx.round() as i32, p.1 + dy.round() as i32);
            // Right of the point the box starts at (x, y); left of it, it
            // ends there; above and below it is centred.
            let left = if dx > 2.0 {
                x
            } else if dx < -2.0 {
                x - size.0
            } else {
                x - size.0 / 2
            };
            let top = if dy < -2.0 {
                y - size.1
            } else if dy > 2.0 {
                y
            } else {
                y - size.1 / 2
            };
            let b = (left, top, left + size.0, top + size.1);
            let inside = b.0 >= area.0 && b.1 >= area.1 && b.2 <= area.2 && b.3 <= area.3;
            if inside && !taken.iter().any(|t| overlaps(*t, b)) {
                return Some(b);
            }
        }
    }
    None
}

/// The points of one error-against-time plot.
struct Points<'a> {
    /// The method settings, with their `(ms, rmse)`.
    methods: Vec<(&'a CellRecord, (f64, f64))>,
    /// The Monte Carlo curve, by increasing time.
    mc: Vec<(f64, f64)>,
    /// The exact reference's time (its error is 0 by definition).
    exact_ms: Option<f64>,
    /// The Pareto front of the methods' and Monte Carlo's points.
    front: Vec<(f64, f64)>,
    /// The axis floor, where RMSE 0 is drawn: below every measured point.
    floor: f64,
}

/// The chart of an error-against-time plot: log time against log RMSE.
type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;

/// The points of `cells` (those that ran) for group `g`, and the plot's
/// ranges of time and RMSE; `None` when there is nothing to plot.
fn points<'a>(cells: &[&'a CellRecord], g: usize) -> Option<(Points<'a>, (f64, f64), f64)> {
    let cells: Vec<&CellRecord> = cells.iter().copied().filter(|c| c.status == "ok").collect();
    let point = |c: &CellRecord| -> Option<(f64, f64)> {
        let e = c.errors?[g].rmse;
        let t = c.seconds? * 1e3;
        (e > 0.0 && t > 0.0).then_some((t, e))
    };
    let methods: Vec<(&CellRecord, (f64, f64))> = cells
        .iter()
        .filter(|c| c.base != "mc" && c.base != "exact")
        .filter_map(|c| Some((*c, point(c)?)))
        .collect();
    let mut mc: Vec<(f64, f64)> = cells
        .iter()
        .filter(|c| c.base == "mc")
        .filter_map(|c| point(c))
        .collect();
    mc.sort_by(|a, b| a.0.total_cmp(&b.0));
    let exact_ms = cells
        .iter()
        .find(|c| c.base == "exact")
        .and_then(|c| c.seconds)
        .map(|s| s * 1e3)
        .filter(|t| *t > 0.0 && t.is_finite());
    let all: Vec<(f64, f64)> = methods
        .iter()
        .map(|m| m.1)
        .chain(mc.iter().copied())
        .collect();
    if all.is_empty() {
        return None;
    }
    let times = all
        .iter()
        .map(|p| p.0)
        .chain(exact_ms)
        .fold((f64::INFINITY, 0.0f64), |(a, b), t| (a.min(t), b.max(t)));
    let (e0, e1) = all.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.1), b.max(p.1))
    });
    let points = Points {
        methods,
        mc,
        exact_ms,
        front: pareto(&all),
        floor: e0 / 3.0,
    };
    Some((points, times, e1))
}

/// Error (RMSE of `V` over group `g`) against time (ms) on `scene`, whose
/// cells are `cells`, as SVG text; `None` when there is nothing to plot.
///
/// The exact reference has RMSE 0, off a log axis: it is drawn as a
/// labelled marker on the axis floor at its time. Method settings are
/// labelled by name, each label placed where it meets no other label or
/// point (a leader line to its point when moved off it).
pub(crate) fn error_against_time(
    config: &ConfigRecord,
    scene: &SceneRecord,
    cells: &[&CellRecord],
    g: usize,
) -> Option<String> {
    let (points, (t0, t1), e1) = self::points(cells, g)?;
    let floor = points.floor;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1100, 720)).into_drawing_area();
        let caption = format!(
            "{}: RMSE of V ({} receivers) against time",
            scene.name, GROUPS[g]
        );
        let mut chart = framed(&root, caption, 60)?
            .build_cartesian_2d(
                (t0 / 1.5..t1 * 1.5).log_scale(),
                (floor..(e1 * 1.5).min(1.5)).log_scale(),
            )
            .ok()?;
        chart
            .configure_mesh()
            .x_desc("time of method::run (ms, median)")
            .y_desc(format!(
                "RMSE of V, {} (the floor: RMSE 0, the exact reference)",
                GROUPS[g]
            ))
            .x_label_formatter(&|v| short(*v))
            .y_label_formatter(&|v| short(*v))
            .draw()
            .ok()?;
        draw_points(&mut chart, config, &points)?;
        legend(&mut chart, SeriesLabelPosition::UpperRight)?;
        draw_labels(&root, &chart, &points)?;
        root.present().ok()?;
    }
    Some(svg)
}

/// The Monte Carlo curve, the Pareto front, the exact reference's marker
/// and the methods' points, with their legend entries.
fn draw_points(
    chart: &mut Chart<'_, '_>,
    config: &ConfigRecord,
    points: &Points<'_>,
) -> Option<()> {
    let Points {
        methods,
        mc,
        exact_ms,
        front,
        floor,
    } = points;
    if mc.len() >= 2 {
        chart
            .draw_series(LineSeries::new(mc.clone(), BLACK.stroke_width(2)))
            .ok()?
            .label(format!(
                "Monte Carlo, {} … {} samples",
                config.mc.first().copied().unwrap_or(0),
                config.mc.last().copied().unwrap_or(0)
            ))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
        chart
            .draw_series(mc.iter().map(|&p| Circle::new(p, 3, BLACK.filled())))
            .ok()?;
    }
    if front.len() >= 2 {
        chart
            .draw_series(DashedLineSeries::new(
                front.clone(),
                6,
                4,
                BLACK.stroke_width(1),
            ))
            .ok()?
            .label("Pareto front (ringed: no point both faster and closer)")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK));
    }
    chart
        .draw_series(
            front
                .iter()
                .map(|&p| Circle::new(p, 8, BLACK.stroke_width(1))),
        )
        .ok()?;
    if let Some(t) = *exact_ms {
        // A downward triangle standing on the floor at the exact
        // reference's time.
        let exact_colour = RGBColor(0, 0, 0);
        chart
            .draw_series(std::iter::once(Polygon::new(
                vec![
                    (t / 1.12, floor * 1.22),
                    (t * 1.12, floor * 1.22),
                    (t, floor * 1.02),
                ],
                exact_colour.filled(),
            )))
            .ok()?
            .label("exact reference: RMSE 0, drawn on the floor at its time")
            .legend(move |(x, y)| {
                Polygon::new(
                    vec![(x + 4, y - 5), (x + 16, y - 5), (x + 10, y + 5)],
                    exact_colour.filled(),
                )
            });
    }
    for (c, p) in methods {
        chart
            .draw_series(std::iter::once(Circle::new(
                *p,
                4,
                colour(&c.base).filled(),
            )))
            .ok()?;
    }
    Some(())
}

/// The labels, placed in pixels: every point and the legend are
/// obstacles, then each label placed takes its box.
fn draw_labels(
    root: &DrawingArea<SVGBackend<'_>, Shift>,
    chart: &Chart<'_, '_>,
    points: &Points<'_>,
) -> Option<()> {
    let (methods, mc, front) = (&points.methods, &points.mc, &points.front);
    let (exact_ms, floor) = (points.exact_ms, points.floor);
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    let area = (xr.start, yr.start, xr.end, yr.end);
    let at = |p: (f64, f64)| chart.backend_coord(&p);
    let dot = |(x, y): (i32, i32), r: i32| (x - r, y - r, x + r, y + r);
    let mut taken: Vec<LabelBox> = methods
        .iter()
        .map(|m| dot(at(m.1), 5))
        .chain(mc.iter().map(|&p| dot(at(p), 4)))
        .chain(front.iter().map(|&p| dot(at(p), 9)))
        .collect();
    // The legend: upper right, up to four lines of about 60 characters.
    let entries = 2 + i32::from(exact_ms.is_some()) + i32::from(front.len() >= 2);
    taken.push((area.2 - 440, area.1, area.2, area.1 + 14 + 20 * entries));
    let font = ("sans-serif", 11).into_font();
    let mut labels = Vec::new();
    if let Some(t) = exact_ms {
        let p = at((t, floor * 1.12));
        taken.push(dot(p, 7));
        labels.push((format!("exact: RMSE 0, {} ms", short(t)), p, BLACK));
    }
    // Crowded points first: the ones with the most neighbours within
    // 40 pixels take the nearest places.
    let mut order: Vec<usize> = (0..methods.len()).collect();
    let crowd = |k: usize| {
        let p = at(methods[k].1);
        methods
            .iter()
            .filter(|m| {
                let q = at(m.1);
                (q.0 - p.0).abs() < 40 && (q.1 - p.1).abs() < 40
            })
            .count()
    };
    order.sort_by_key(|&k| std::cmp::Reverse(crowd(k)));
    for k in order {
        let (c, p) = methods[k];
        labels.push((c.method.clone(), at(p), colour(&c.base)));
    }
    for (text, p, col) in labels {
        let size = label_size(&text);
        let Some(b) = place_label(p, size, area, &taken) else {
            continue;
        };
        taken.push(b);
        // A leader line from the point to the box's nearest side when
        // the label is not beside it.
        let (cx, cy) = (p.0.clamp(b.0, b.2), p.1.clamp(b.1, b.3));
        if (cx - p.0).abs().max((cy - p.1).abs()) > 9 {
            root.draw(&PathElement::new(vec![p, (cx, cy)], col.mix(0.6)))
                .ok()?;
        }
        root.draw(&Text::new(text, (b.0 + 1, b.1), font.clone().color(&col)))
            .ok()?;
    }
    Some(())
}

/// `V` along the scene's profile row: the exact answer and the default
/// setting of each method that ran (of `cells`, the scene's), as SVG text.
pub(crate) fn profile(scene: &SceneRecord, cells: &[&CellRecord]) -> Option<String> {
    let columns = &scene.profile_columns;
    let (&first, &last) = (columns.first()?, columns.last()?);
    let (x0, x1) = (
        f64::from(first),
        f64::from(last).max(f64::from(first) + 1.0),
    );
    let cells: Vec<&CellRecord> = cells
        .iter()
        .copied()
        .filter(|c| {
            c.status == "ok"
                && c.base != "exact"
                && c.base != "mc"
                && c.profile.len() == scene.profile_columns.len()
                && super::is_default_setting(&c.method)
        })
        .collect();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 480)).into_drawing_area();
        let caption = format!(
            "{}: V along image row {} (the row with the most penumbra)",
            scene.name, scene.profile_row
        );
        let mut chart = framed(&root, caption, 50)?
            .build_cartesian_2d(x0..x1, -0.02f64..1.02)
            .ok()?;
        chart
            .configure_mesh()
            .x_desc("image column")
            .y_desc("V")
            .draw()
            .ok()?;
        let line = |values: &[f64]| -> Vec<(f64, f64)> {
            columns
                .iter()
                .zip(values)
                .map(|(&c, &v)| (f64::from(c), v))
                .collect()
        };
        for c in &cells {
            let col = colour(&c.base);
            chart
                .draw_series(LineSeries::new(line(&c.profile), col.stroke_width(1)))
                .ok()?
                .label(c.method.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], col));
        }
        chart
            .draw_series(LineSeries::new(
                line(&scene.profile_exact),
                BLACK.stroke_width(3),
            ))
            .ok()?
            .label("exact")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(3)));
        legend(&mut chart, SeriesLabelPosition::LowerRight)?;
        root.present().ok()?;
    }
    Some(svg)
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_pareto_front_keeps_the_undominated() {
        let p = [(1.0, 0.5), (2.0, 0.2), (3.0, 0.3), (4.0, 0.1), (2.0, 0.25)];
        assert_eq!(super::pareto(&p), vec![(1.0, 0.5), (2.0, 0.2), (4.0, 0.1)]);
        // Against the definition, on small integers: ties in time and in
        // error, repeated points.
        let mut seed = 7u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            f64::from((seed >> 60) as u32)
        };
        for _ in 0..200 {
            let p: Vec<(f64, f64)> = (0..12).map(|_| (next(), next())).collect();
            let mut brute: Vec<(f64, f64)> = p
                .iter()
                .copied()
                .filter(|&(t, e)| {
                    !p.iter()
                        .any(|&(t2, e2)| t2 <= t && e2 <= e && (t2 < t || e2 < e))
                })
                .collect();
            brute.sort_by(|a, b| a.0.total_cmp(&b.0));
            brute.dedup();
            assert_eq!(super::pareto(&p), brute, "{p:?}");
        }
    }

    #[test]
    fn labels_of_a_crowd_of_points_never_overlap_and_stay_inside() {
        // Thirty points within 20 pixels of one another.
        let area = (0, 0, 900, 600);
        let points: Vec<(i32, i32)> = (0..30)
            .map(|k| (400 + (k * 7) % 20, 300 + (k * 13) % 20))
            .collect();
        let mut taken: Vec<super::LabelBox> = points
            .iter()
            .map(|&(x, y)| (x - 5, y - 5, x + 5, y + 5))
            .collect();
        let obstacles = taken.len();
        for (k, &p) in points.iter().enumerate() {
            let size = super::label_size(&format!("method-{k}:option,other"));
            let b = super::place_label(p, size, area, &taken).expect("a place");
            assert!(b.0 >= 0 && b.1 >= 0 && b.2 <= 900 && b.3 <= 600);
            assert!(taken.iter().all(|t| !super::overlaps(*t, b)));
            taken.push(b);
        }
        assert_eq!(taken.len(), obstacles + 30);
    }
}

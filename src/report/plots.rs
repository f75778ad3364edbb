//! The report's SVG plots, drawn with `plotters`: error against time per
//! scene and receiver group (log–log, every method setting a point, Monte
//! Carlo a curve, the Pareto front marked), and the falloff profile across
//! one penumbra per scene.

use super::{CellRecord, ConfigRecord, SceneRecord, GROUPS};
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

/// Error (RMSE of `V` over group `g`) against time (ms) on `scene`, whose
/// cells are `cells`, as SVG text; `None` when there is nothing to plot.
pub(crate) fn error_against_time(
    config: &ConfigRecord,
    scene: &SceneRecord,
    cells: &[&CellRecord],
    g: usize,
) -> Option<String> {
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
    let all: Vec<(f64, f64)> = methods
        .iter()
        .map(|m| m.1)
        .chain(mc.iter().copied())
        .collect();
    if all.is_empty() {
        return None;
    }
    let (t0, t1) = all.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.0), b.max(p.0))
    });
    let (e0, e1) = all.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.1), b.max(p.1))
    });
    let front = pareto(&all);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 620)).into_drawing_area();
        root.fill(&WHITE).ok()?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!(
                    "{}: RMSE of V ({} receivers) against time",
                    scene.name, GROUPS[g]
                ),
                ("sans-serif", 20),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(
                (t0 / 1.5..t1 * 1.5).log_scale(),
                (e0 / 1.5..(e1 * 1.5).min(1.5)).log_scale(),
            )
            .ok()?;
        chart
            .configure_mesh()
            .x_desc("time of method::run (ms, median)")
            .y_desc(format!("RMSE of V, {}", GROUPS[g]))
            .x_label_formatter(&|v| short(*v))
            .y_label_formatter(&|v| short(*v))
            .draw()
            .ok()?;
        if mc.len() >= 2 {
            chart
                .draw_series(LineSeries::new(mc.clone(), BLACK.stroke_width(2)))
                .ok()?
                .label(format!(
                    "Monte Carlo, {} … {} samples",
                    config.mc.first().copied().unwrap_or(0),
                    config.mc.last().copied().unwrap_or(0)
                ))
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2))
                });
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
        for (c, p) in &methods {
            let col = colour(&c.base);
            chart
                .draw_series(std::iter::once(
                    EmptyElement::at(*p)
                        + Circle::new((0, 0), 4, col.filled())
                        + Text::new(
                            c.method.clone(),
                            (6, -4),
                            ("sans-serif", 10).into_font().color(&col),
                        ),
                ))
                .ok()?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .ok()?;
        root.present().ok()?;
    }
    Some(svg)
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
        root.fill(&WHITE).ok()?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!(
                    "{}: V along image row {} (the row with the most penumbra)",
                    scene.name, scene.profile_row
                ),
                ("sans-serif", 20),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(50)
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
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .ok()?;
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
}

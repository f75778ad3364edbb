//! The report against independent answers: one cell's RMSE recomputed
//! from the buffers without the report's code, and a sweep run in three
//! shards and merged equal to the sweep run whole, timings aside.

use softshadow::method::{self, Exact};
use softshadow::render::{Frame, Stages};
use softshadow::report::{self, Case, Config, Results, Shard};
use softshadow::scene::builtin;

fn cases(names: &[&str]) -> Vec<Case> {
    names
        .iter()
        .map(|n| Case {
            name: (*n).to_owned(),
            scene: builtin(n).unwrap(),
        })
        .collect()
}

fn small(methods: &[&str]) -> Config {
    Config {
        side: 40,
        runs: 1,
        mc: vec![2, 4, 8],
        methods: methods.iter().map(|s| (*s).to_owned()).collect(),
        shard: None,
        picture_side: 0,
        ..Config::default()
    }
}

fn quiet(_: usize, _: usize, _: &str) {}

#[test]
fn a_cell_s_rmse_is_the_buffers_rmse() {
    let config = small(&["pcss:map=256"]);
    let results = report::finish(report::run(&cases(&["contact"]), &config, None, &quiet).unwrap());
    let cell = results
        .cells
        .iter()
        .find(|c| c.method == "pcss:map=256")
        .unwrap();
    let e = cell.errors.unwrap();
    // Independently: the same frame, both methods run directly, the RMSE
    // summed by hand.
    let scene = builtin("contact").unwrap();
    let camera = scene.camera().unwrap().with_resolution(40, 40).unwrap();
    let stages = Stages::new(&scene);
    let frame = Frame::from_camera(&camera, stages.bvh());
    let exact = method::run(&Exact, &stages, &frame)
        .unwrap()
        .output
        .visibility;
    let pcss = method::parse("pcss:map=256").unwrap();
    let v = method::run(pcss.as_ref(), &Stages::new(&scene), &frame)
        .unwrap()
        .output
        .visibility;
    let rmse = |keep: &dyn Fn(usize) -> bool| {
        let (mut sum, mut n) = (0.0, 0usize);
        for i in 0..v.len() {
            if keep(i) {
                sum += (v[i] - exact[i]) * (v[i] - exact[i]);
                n += 1;
            }
        }
        ((sum / n as f64).sqrt(), n)
    };
    let (all, n) = rmse(&|_| true);
    let (pen, m) = rmse(&|i| exact[i] > 0.0 && exact[i] < 1.0);
    assert_eq!((e[0].count, e[1].count), (n, m));
    assert!((e[0].rmse - all).abs() < 1e-12, "{} vs {all}", e[0].rmse);
    assert!((e[1].rmse - pen).abs() < 1e-12, "{} vs {pen}", e[1].rmse);
    assert!(all > 0.0 && pen > all);
}

/// The results with everything that depends on the clock or the machine
/// zeroed.
fn untimed(mut r: Results) -> Results {
    r.machines.clear();
    for s in &mut r.scenes {
        s.shared = [0.0; 2];
        s.machine = 0;
    }
    for c in &mut r.cells {
        c.runs.clear();
        c.seconds = None;
        c.speedup = None;
        c.machine = 0;
    }
    for y in r.yardsticks.values_mut() {
        y.seconds = report::Line { c: 0.0, d: 0.0 };
    }
    r
}

#[test]
fn three_shards_merged_are_the_whole_sweep() {
    let names = ["contact", "linear-light"];
    let config = small(&["hard", "pcss:map=256", "oess:map=128"]);
    let whole = report::finish(report::run(&cases(&names), &config, None, &quiet).unwrap());
    let parts: Vec<Results> = (1..=3)
        .map(|index| {
            let config = Config {
                shard: Some(Shard { index, count: 3 }),
                ..config.clone()
            };
            report::run(&cases(&names), &config, None, &quiet).unwrap()
        })
        .collect();
    // Each part holds a third of the cells, none twice.
    let counts: Vec<usize> = parts.iter().map(|p| p.cells.len()).collect();
    assert_eq!(
        counts.iter().sum::<usize>(),
        whole.cells.len(),
        "{counts:?}"
    );
    let merged = report::merge(parts.clone()).unwrap();
    // The derived columns were computed at the merge.
    assert!(merged.yardsticks.contains_key("contact"));
    assert!(merged.cells.iter().any(|c| c.mc_equal.is_some()));
    let (a, b) = (untimed(whole), untimed(merged));
    assert_eq!(
        serde_json::to_string(&a).unwrap(),
        serde_json::to_string(&b).unwrap()
    );
    // A part given twice is refused.
    assert!(report::merge(vec![parts[0].clone(), parts[0].clone()]).is_err());
    // The n/a cells say why.
    assert!(a.cells.iter().any(|c| c.scene == "contact"
        && c.method == "oess:map=128"
        && c.status == "n/a (sphere light)"));
}

/// A method of one's own reaches the report through `Config::own`: the
/// registry's `hard` under another name gives the same cell as `hard`.
#[test]
fn a_method_of_ones_own_is_swept_like_the_registrys() {
    #[derive(Debug)]
    struct Mine(softshadow::method::HardShadow);
    impl softshadow::Method for Mine {
        fn name(&self) -> String {
            "my-hard".into()
        }
        fn needs(&self) -> softshadow::render::Needs {
            self.0.needs()
        }
        fn visibility(
            &self,
            input: &softshadow::method::Input<'_, '_>,
        ) -> Result<softshadow::method::Output, softshadow::method::MethodError> {
            self.0.visibility(input)
        }
    }
    let config = Config {
        own: vec![std::sync::Arc::new(Mine(Default::default()))],
        ..small(&["hard"])
    };
    let results = report::finish(report::run(&cases(&["contact"]), &config, None, &quiet).unwrap());
    let cell = |name: &str| results.cells.iter().find(|c| c.method == name).unwrap();
    let (mine, hard) = (cell("my-hard"), cell("hard"));
    assert_eq!(mine.status, "ok");
    assert_eq!(mine.errors, hard.errors);
    assert_eq!(mine.shaded, hard.shaded);
    assert!(mine.mc_equal.is_some());
}

#[test]
fn the_error_plots_show_exact_on_the_floor_and_every_setting_labelled_apart() {
    let settings = [
        "pcss",
        "pcss:map=256",
        "sism",
        "sism:horizon",
        "hard",
        "hard:horizon",
    ];
    let config = small(&settings);
    let results = report::finish(report::run(&cases(&["contact"]), &config, None, &quiet).unwrap());
    let dir = std::env::temp_dir().join(format!("softshadow-report-plots-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    report::write(&results, &dir).unwrap();
    let svg = std::fs::read_to_string(dir.join("plots/contact-all.svg")).unwrap();
    let exact_ms = results
        .cells
        .iter()
        .find(|c| c.method == "exact")
        .and_then(|c| c.seconds)
        .unwrap()
        * 1e3;
    // The texts drawn, with their positions.
    let texts: Vec<(f64, f64, String)> = svg
        .split("<text")
        .skip(1)
        .filter_map(|t| {
            let attr = |name: &str| -> Option<f64> {
                let at = t.find(&format!(" {name}=\""))? + name.len() + 3;
                t[at..].split('"').next()?.parse().ok()
            };
            let body = t
                .split_once('>')?
                .1
                .split("</text>")
                .next()?
                .trim()
                .to_owned();
            Some((attr("x")?, attr("y")?, body))
        })
        .collect();
    let exact: Vec<_> = texts
        .iter()
        .filter(|t| t.2.starts_with("exact: RMSE 0"))
        .collect();
    assert_eq!(exact.len(), 1, "{texts:?}");
    let shown: f64 = exact[0]
        .2
        .split(", ")
        .nth(1)
        .unwrap()
        .trim_end_matches(" ms")
        .parse()
        .unwrap();
    assert!(
        (shown - exact_ms).abs() <= 0.01 * exact_ms,
        "{shown} vs {exact_ms}"
    );
    let labels: Vec<_> = texts
        .iter()
        .filter(|t| settings.contains(&t.2.as_str()))
        .collect();
    for s in settings {
        assert_eq!(
            labels.iter().filter(|t| t.2 == s).count(),
            1,
            "{s}: {texts:?}"
        );
    }
    // Estimated boxes (11 px text, at most 6 px a character) apart.
    let boxes: Vec<(f64, f64, f64, f64)> = labels
        .iter()
        .map(|(x, y, s)| (*x, *y, x + 6.0 * s.len() as f64, y + 11.0))
        .collect();
    for (i, a) in boxes.iter().enumerate() {
        for b in &boxes[i + 1..] {
            let apart = a.2 <= b.0 || b.2 <= a.0 || a.3 <= b.1 || b.3 <= a.1;
            assert!(apart, "labels overlap: {a:?} {b:?}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

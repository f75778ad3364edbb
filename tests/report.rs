//! The report against independent answers: one cell's RMSE recomputed
//! from the buffers without the report's code, and a sweep run in three
//! shards and merged equal to the sweep run whole, timings aside.

use softshadow::method::{self, Exact};
use softshadow::render::{Frame, Stages};
use softshadow::report::{self, Case, Config, ReportError, Results, Shard};
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
    // The scene's largest certified bound is the largest of the exact
    // reference's bounds over the frame's receivers, asked directly.
    let bounds = softshadow::reference::exact::visibility_many_bounded(
        stages.bvh(),
        scene.light(),
        &frame.positions(),
    );
    let largest = bounds.iter().map(|b| b.unwrap().bound).fold(0.0, f64::max);
    assert!(largest > 0.0 && largest < 1.0, "{largest}");
    assert_eq!(results.scenes[0].exact_bound, Some(largest));
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

// ---------------------------------------------------------------------
// Hostile and inconsistent parts (issue 39): each refused whole, before
// anything is written; names that flatten alike kept apart; a scene that
// cannot be prepared said.

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("softshadow-report-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn as_json(r: &Results) -> serde_json::Value {
    serde_json::to_value(r).unwrap()
}

fn from_json(v: serde_json::Value) -> Results {
    serde_json::from_value(v).unwrap()
}

/// The error of a merge that must be refused (no dump of the results
/// when it is not).
fn refusal(merged: Result<Results, ReportError>) -> ReportError {
    match merged {
        Ok(_) => panic!("merged what must be refused"),
        Err(e) => e,
    }
}

/// A part's profile longer than its columns used to pass the merge and
/// panic in the plots with `--out` half-written.
#[test]
fn a_part_whose_profile_outruns_its_columns_is_refused_before_anything_is_written() {
    let part = report::run(&cases(&["contact"]), &small(&["hard"]), None, &quiet).unwrap();
    let mut v = as_json(&part);
    v["scenes"][0]["profile_exact"]
        .as_array_mut()
        .unwrap()
        .push(0.5.into());
    let bad = from_json(v);
    let err = refusal(report::merge(vec![bad.clone()]));
    assert!(
        matches!(&err, ReportError::NotWhole { what, .. } if what.contains("profile")),
        "{err:?}"
    );
    let dir = tmp("profile");
    assert!(matches!(
        report::write(&bad, &dir),
        Err(ReportError::NotWhole { .. })
    ));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
}

/// Monte Carlo's RMSE falling from 1 at N = 2 to the smallest positive
/// double at N = 4: the fitted power law's factor, `e^744`, is beyond
/// `f64`; it used to be written as `null`, which the merge could not read
/// back.
#[test]
fn every_number_written_reads_back() {
    let config = Config {
        mc: vec![2, 4],
        ..small(&["hard"])
    };
    let part = report::run(&cases(&["contact"]), &config, None, &quiet).unwrap();
    let mut v = as_json(&part);
    for c in v["cells"].as_array_mut().unwrap() {
        let rmse = match c["method"].as_str().unwrap() {
            "mc:2" => 1.0,
            "mc:4" => f64::from_bits(1),
            _ => continue,
        };
        c["errors"][0]["rmse"] = rmse.into();
    }
    let merged = report::merge(vec![from_json(v)]).unwrap();
    let text = serde_json::to_string(&merged).unwrap();
    let back: Results = serde_json::from_str(&text).unwrap();
    assert_eq!(back, merged);
    // And the merge takes its own output.
    assert_eq!(report::merge(vec![back]).unwrap(), merged);
}

fn shard_of(index: u32, names: &[&str], methods: &[&str]) -> Results {
    let config = Config {
        shard: Some(Shard { index, count: 2 }),
        ..small(methods)
    };
    report::run(&cases(names), &config, None, &quiet).unwrap()
}

/// Parts of another scene list, another method list (the same number of
/// cells either way), a foreign format, a cell beyond the sweep, a
/// miscounted sweep: each used to merge into a report that looked whole.
#[test]
fn parts_of_different_sweeps_are_refused() {
    let a = shard_of(1, &["contact", "comb"], &["hard"]);
    // Whole parts of two sweeps are `Parts`; a part that is not whole in
    // itself is `NotWhole`, the part named.
    let refused = |parts: Vec<Results>, needle: &str, whole: bool| {
        let err = refusal(report::merge(parts));
        let kind = if whole {
            matches!(err, ReportError::Parts { .. })
        } else {
            matches!(&err, ReportError::NotWhole { part: Some(p), .. } if p == "part 1")
        };
        assert!(kind, "{err:?}");
        let err = err.to_string();
        assert!(err.contains(needle), "{err:?} lacks {needle:?}");
        assert!(!err.contains('\n'), "{err:?}");
    };
    refused(
        vec![
            a.clone(),
            shard_of(2, &["contact", "linear-light"], &["hard"]),
        ],
        "scenes",
        true,
    );
    refused(
        vec![a.clone(), shard_of(2, &["contact", "comb"], &["pcss"])],
        "settings",
        true,
    );
    let mut v = as_json(&a);
    v["format"] = "softshadow-report/0".into();
    refused(vec![from_json(v)], "format", false);
    let mut v = as_json(&a);
    v["cells"][0]["index"] = 10_000.into();
    refused(vec![from_json(v)], "beyond", false);
    let mut v = as_json(&a);
    v["config"]["cells"] = 1.into();
    refused(vec![from_json(v)], "cells", false);
}

/// Two parts of 100,000 cells each: the merge used to check each cell
/// against every cell before it (minutes); now linear. The limit only
/// stops a quadratic merge from hanging the suite: it is about a hundred
/// times what the merge takes.
#[test]
fn a_large_merge_is_linear() {
    let scenes: Vec<String> = (0..1000).map(|k| format!("scene-{k}")).collect();
    let mut settings = vec!["exact".to_owned()];
    settings.extend((0..198).map(|k| format!("own-{k}")));
    settings.extend(["mc:2".to_owned(), "mc:4".to_owned()]);
    let total = scenes.len() * settings.len();
    let empty = serde_json::json!({
        "format": report::FORMAT,
        "config": {"side": 16, "runs": 1, "mc": [2, 4], "pictures": 0,
                   "scenes": scenes, "settings": settings, "cells": total},
        "machines": ["a machine"],
        "scenes": [],
        "cells": [],
        "yardsticks": {},
    });
    let parts: Vec<Results> = (0..2)
        .map(|p| {
            let mut part = from_json(empty.clone());
            part.cells = (p..total)
                .step_by(2)
                .map(|k| report::CellRecord {
                    index: k,
                    scene: scenes[k / settings.len()].clone(),
                    method: settings[k % settings.len()].clone(),
                    base: settings[k % settings.len()]
                        .split(':')
                        .next()
                        .unwrap()
                        .to_owned(),
                    status: "error: the scene has no camera".to_owned(),
                    machine: 0,
                    runs: Vec::new(),
                    seconds: None,
                    errors: None,
                    shaded: None,
                    pieces: None,
                    profile: Vec::new(),
                    picture: None,
                    mc_equal: None,
                    mc_equal_penumbra: None,
                    speedup: None,
                })
                .collect();
            part
        })
        .collect();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(report::merge(parts).map(|r| r.cells.len()));
    });
    let merged = rx
        .recv_timeout(std::time::Duration::from_secs(60))
        .expect("the merge of 2 × 100,000 cells ends within a minute");
    assert_eq!(merged.unwrap(), total);
}

/// `con tact` and `con-tact` flatten to the same file name: their
/// pictures and plots used to overwrite each other.
#[test]
fn scenes_whose_names_flatten_alike_keep_their_own_files() {
    let config = Config {
        side: 16,
        picture_side: 8,
        ..small(&["hard"])
    };
    let cases: Vec<Case> = ["con tact", "con-tact", "CON-TACT"]
        .iter()
        .map(|n| Case {
            name: (*n).to_owned(),
            scene: builtin("contact").unwrap(),
        })
        .collect();
    let dir = tmp("alike");
    let results = report::finish(report::run(&cases, &config, Some(&dir), &quiet).unwrap());
    report::write(&results, &dir).unwrap();
    let pictures: Vec<&str> = results
        .cells
        .iter()
        .filter_map(|c| c.picture.as_deref())
        .collect();
    // `exact` and `hard` on each scene, each its own file (compared
    // without case: some file systems do).
    assert_eq!(pictures.len(), 6, "{pictures:?}");
    let distinct: std::collections::HashSet<String> =
        pictures.iter().map(|p| p.to_lowercase()).collect();
    assert_eq!(distinct.len(), 6, "{pictures:?}");
    for p in &pictures {
        assert!(dir.join(p).is_file(), "{p}");
    }
    // Each scene's section of the index links plots of its own.
    let index = std::fs::read_to_string(dir.join("index.md")).unwrap();
    let plots: Vec<&str> = index
        .lines()
        .filter(|l| l.starts_with("![plots/"))
        .collect();
    let distinct: std::collections::HashSet<String> =
        plots.iter().map(|p| p.to_lowercase()).collect();
    assert!(plots.len() >= 3 * 2, "{plots:?}");
    assert_eq!(distinct.len(), plots.len(), "{plots:?}");
    // Each scene's paragraph states its exact answers' largest bound.
    for s in &results.scenes {
        let b = s.exact_bound.expect("recorded");
        let said = format!("the exact answers' largest certified bound {b:.1e}");
        assert_eq!(index.matches(&said).count(), 3, "{said}");
    }
}

/// A 245-character scene name (a long path) used to make a picture name
/// longer than a file name may be.
#[test]
fn a_long_scene_name_makes_file_names_within_limits() {
    let config = Config {
        side: 16,
        picture_side: 8,
        ..small(&["hard"])
    };
    let case = Case {
        name: format!("/{}/scene.json", "d".repeat(232)),
        scene: builtin("contact").unwrap(),
    };
    let dir = tmp("long");
    let results = report::finish(report::run(&[case], &config, Some(&dir), &quiet).unwrap());
    report::write(&results, &dir).unwrap();
    let mut files = 0;
    let mut stack = vec![dir.clone()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let path = e.unwrap().path();
            assert!(path.file_name().unwrap().len() <= 100, "{}", path.display());
            if path.is_dir() {
                stack.push(path);
            } else {
                files += 1;
            }
        }
    }
    // results.json, index.md, two pictures, at least two plots.
    assert!(files >= 6, "{files}");
}

/// A scene whose receivers are inside its light cannot be prepared: the
/// index used to be silent about it.
#[test]
fn a_scene_that_cannot_be_prepared_is_said_in_the_index() {
    let scene = softshadow::scene::file::scene_from_str(
        "inside.json",
        r#"{"light": {"type": "sphere", "center": [0, 0.2, 0], "radius": 0.5},
            "camera": {"eye": [0, 2, 6], "target": [0, 0, 0], "fov_y_deg": 40, "width": 24, "height": 18},
            "meshes": [{"name": "floor", "primitive": {"type": "quad", "center": [0, 0, 0], "u": [4, 0, 0], "v": [0, 0, 4]}}]}"#,
        std::path::Path::new("."),
    )
    .unwrap();
    let mut all = cases(&["contact"]);
    all.push(Case {
        name: "inside".to_owned(),
        scene,
    });
    let results = report::finish(report::run(&all, &small(&["hard"]), None, &quiet).unwrap());
    let dir = tmp("unprepared");
    report::write(&results, &dir).unwrap();
    let index = std::fs::read_to_string(dir.join("index.md")).unwrap();
    let line = index
        .lines()
        .find(|l| l.contains("could not be prepared"))
        .unwrap_or_else(|| panic!("{index}"));
    let _ = line;
    assert!(
        index
            .lines()
            .any(|l| l.contains("`inside`") && l.contains("inside the sphere light")),
        "{index}"
    );
}

/// A picture side of 2³¹ used to overflow (twice it, for the scene named
/// `default`) to a picture of 9 × 2; a side beyond the frame is the
/// frame's: the same picture as at the frame's side.
#[test]
fn a_picture_side_beyond_the_frame_is_the_frame() {
    let picture = |picture_side: u32| {
        let config = Config {
            side: 16,
            picture_side,
            ..small(&["hard"])
        };
        let case = Case {
            name: "default".to_owned(),
            scene: builtin("contact").unwrap(),
        };
        let dir = tmp(&format!("picture-side-{picture_side}"));
        let results = report::run(&[case], &config, Some(&dir), &quiet).unwrap();
        let name = results.cells[1].picture.clone().unwrap();
        let file = std::io::BufReader::new(std::fs::File::open(dir.join(&name)).unwrap());
        let mut reader = png::Decoder::new(file).read_info().unwrap();
        let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut pixels).unwrap();
        (info.width, info.height, pixels)
    };
    let (w, h, pixels) = picture(1 << 31);
    // The shaded frame (16 wide) beside the heat-map, 4 apart.
    assert!(w > 2 * 16 + 4 && h >= 16, "{w} × {h}");
    assert_eq!((w, h, pixels), picture(16));
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
    let svg = std::fs::read_to_string(dir.join("plots/contact/all.svg")).unwrap();
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

/// On the segment-light scene every receiver is in one group by the
/// light's pieces, the counts are those of the pieces asked receiver by
/// receiver, and each cell's errors per group are the buffers' RMSE over
/// those receivers; other scenes have no such groups. Results without the
/// groups (written before them) still read, check and merge; a cell with
/// them on a scene without them is refused.
#[test]
fn the_groups_by_the_light_s_pieces() {
    use softshadow::kernel::receiver_view::Pieces;
    use softshadow::reference::exact;
    let config = small(&["hard", "oess:map=128"]);
    let results = report::finish(
        report::run(&cases(&["linear-light", "contact"]), &config, None, &quiet).unwrap(),
    );
    let scene = builtin("linear-light").unwrap();
    let camera = scene.camera().unwrap().with_resolution(40, 40).unwrap();
    let stages = Stages::new(&scene);
    let frame = Frame::from_camera(&camera, stages.bvh());
    let kinds: Vec<Pieces> = frame
        .receivers()
        .iter()
        .map(|r| {
            exact::pieces(stages.bvh(), scene.light(), r.position)
                .unwrap()
                .unwrap()
        })
        .collect();
    let counts = Pieces::ALL.map(|k| kinds.iter().filter(|x| **x == k).count());
    let record = &results.scenes[0];
    assert_eq!(record.name, "linear-light");
    assert_eq!(record.pieces, Some(counts));
    assert_eq!(counts.iter().sum::<usize>(), record.receivers);
    // The frame shows the model's case, the others and the lit floor.
    for k in [Pieces::OneAtEnd, Pieces::Several, Pieces::Whole] {
        assert!(kinds.contains(&k), "no receiver sees {k:?}");
    }
    assert_eq!(results.scenes[1].pieces, None);
    let exact_v = method::run(&Exact, &stages, &frame)
        .unwrap()
        .output
        .visibility;
    for setting in ["hard", "oess:map=128"] {
        let cell = results
            .cells
            .iter()
            .find(|c| c.scene == "linear-light" && c.method == setting)
            .unwrap();
        let m = method::parse(setting).unwrap();
        let v = method::run(m.as_ref(), &Stages::new(&scene), &frame)
            .unwrap()
            .output
            .visibility;
        let pieces = cell.pieces.unwrap();
        for (g, kind) in Pieces::ALL.iter().enumerate() {
            let (mut sum, mut n) = (0.0, 0usize);
            for i in (0..v.len()).filter(|&i| kinds[i] == *kind) {
                sum += (v[i] - exact_v[i]) * (v[i] - exact_v[i]);
                n += 1;
            }
            let rmse = if n > 0 { (sum / n as f64).sqrt() } else { 0.0 };
            assert_eq!(pieces[g].count, n, "{setting}, {kind:?}");
            assert!(
                (pieces[g].rmse - rmse).abs() < 1e-12,
                "{setting}, {kind:?}: {} vs {rmse}",
                pieces[g].rmse
            );
        }
    }
    assert!(results
        .cells
        .iter()
        .filter(|c| c.scene == "contact")
        .all(|c| c.pieces.is_none()));
    // Without the groups, as written before them.
    let mut old = as_json(&results);
    let text_with = old.to_string();
    for list in ["scenes", "cells"] {
        for x in old[list].as_array_mut().unwrap() {
            x.as_object_mut().unwrap().remove("pieces");
        }
    }
    assert!(text_with.contains("\"pieces\"") && !old.to_string().contains("\"pieces\""));
    let old = from_json(old);
    old.check().unwrap();
    assert_eq!(
        report::merge(vec![old]).unwrap().cells.len(),
        results.cells.len()
    );
    // A cell with the groups on a scene without them.
    let mut bad = as_json(&results);
    let errors = bad["cells"][1]["pieces"].clone();
    let k = results
        .cells
        .iter()
        .position(|c| c.scene == "contact" && c.status == "ok")
        .unwrap();
    bad["cells"][k]["pieces"] = errors;
    let err = refusal(report::merge(vec![from_json(bad)]));
    assert!(
        matches!(&err, ReportError::NotWhole { what, .. } if what.contains("pieces")),
        "{err:?}"
    );
    // A measured cell of the segment-light scene without them.
    let mut bad = as_json(&results);
    bad["cells"][1].as_object_mut().unwrap().remove("pieces");
    let err = refusal(report::merge(vec![from_json(bad)]));
    assert!(
        matches!(&err, ReportError::NotWhole { what, .. } if what.contains("cells[1].pieces")),
        "{err:?}"
    );
    // The index says the groups under the segment-light scene only.
    let dir = tmp("pieces");
    report::write(&results, &dir).unwrap();
    let index = std::fs::read_to_string(dir.join("index.md")).unwrap();
    let row: Vec<String> = counts.iter().map(usize::to_string).collect();
    let row = format!("| receivers | {} |", row.join(" | "));
    let at = index.find(&row).expect("the table by pieces");
    assert!(index.find("## `linear-light`").unwrap() < at);
    assert!(index.find("## `contact`").unwrap() > at);
    assert_eq!(index.matches("| method | one piece at an end |").count(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}

//! Method options on the command line: an option given twice in a method
//! name, and `--seed` beside a name that sets `seed=` or for a method
//! without a seed, are refused in one line (exit 2), as the scene files
//! refuse a duplicate key; `--seed` alone is the option `seed=`.

#[path = "support/cli.rs"]
mod cli_support;

use cli_support::{refused, softshadow, write};

const POINTS: &str =
    r#"{"points": [{"p": [0.05, 0.0, 0.1]}, {"p": [0.6, 0.0, -0.1]}, {"p": [0.3, 0.0, 0.0]}]}"#;

fn visibility(points: &str, method: &str, seed: Option<&str>) -> std::process::Output {
    let mut args = vec![
        "visibility",
        "--scene",
        "default",
        "--points",
        points,
        "--method",
        method,
    ];
    if let Some(s) = seed {
        args.extend(["--seed", s]);
    }
    softshadow(&args)
}

#[test]
fn seed_conflicts_and_repeated_options_are_refused() {
    let d = cli_support::dir("options", "seed");
    let points = write(&d, "points.json", POINTS);
    // `--seed` and `seed=` in the name: which wins would be a guess.
    for method in ["mc:64,seed=3", "mc:seed=3,64"] {
        refused(
            &visibility(&points, method, Some("4")),
            300,
            &["--seed 4", "seed=", "once"],
        );
    }
    // `--seed` for a method without a seed: it would be ignored.
    for method in ["exact", "pcss", "hard"] {
        refused(
            &visibility(&points, method, Some("4")),
            300,
            &["--seed 4", method, "no seed", "mc:N"],
        );
    }
    refused(
        &softshadow(&[
            "render",
            "--scene",
            "default",
            "--method",
            "pcss",
            "--seed",
            "4",
            "--out",
            d.join("out").to_str().unwrap(),
        ]),
        300,
        &["--seed 4", "pcss", "no seed"],
    );
    // An option given twice in the name, equal or not.
    for (method, key) in [
        ("mc:64,seed=3,seed=4", "seed"),
        ("mc:64,seed=3,seed=3", "seed"),
        ("mc:64,128", "N"),
        ("pcss:map=64,map=128", "map"),
    ] {
        refused(
            &visibility(&points, method, None),
            1000,
            &[method, key, "given twice"],
        );
    }
}

#[test]
fn seed_alone_is_the_seed_option() {
    // Floor points in the bunny's penumbra, where the samples matter.
    use softshadow::bvh::{Bvh, Occluders};
    use softshadow::definitions::in_penumbra;
    use softshadow::reference::exact;
    use softshadow::scene::builtin::{builtin, floor_receivers};
    let scene = builtin("default").unwrap();
    let bvh = Bvh::new(Occluders::from_scene(&scene));
    let penumbra: Vec<String> = floor_receivers(&scene, 24)
        .into_iter()
        .filter(|&p| in_penumbra(exact::visibility(&bvh, scene.light(), p).unwrap()))
        .take(4)
        .map(|p| format!(r#"{{"p": [{:?}, {:?}, {:?}]}}"#, p.x, p.y, p.z))
        .collect();
    assert_eq!(penumbra.len(), 4);
    let d = cli_support::dir("options", "same");
    let points = write(
        &d,
        "points.json",
        &format!(r#"{{"points": [{}]}}"#, penumbra.join(", ")),
    );
    let answer = |out: std::process::Output| {
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        (json["method"].clone(), json["visibility"].clone())
    };
    let by_flag = answer(visibility(&points, "mc:64", Some("7")));
    let by_option = answer(visibility(&points, "mc:64,seed=7", None));
    assert_eq!(by_flag, by_option);
    assert_eq!(by_flag.0, "mc:64,seed=7");
    let other = answer(visibility(&points, "mc:64", Some("8")));
    assert_ne!(by_flag.1, other.1, "the seed changes the samples");
}

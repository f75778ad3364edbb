//! The file names of a report: every scene and every setting of a sweep
//! gets a *stem*, its name flattened to letters, digits and `-`, cut to
//! [`STEM_MAX`] bytes and made unique within its list (ignoring case, as
//! some file systems do) by a suffix `-2`, `-3`, …; a picture is
//! `pictures/SCENE/SETTING.png`, a plot `plots/SCENE/WHAT.svg`. The stems
//! are a function of the sweep's lists alone ([`ConfigRecord`]), so every
//! part of a sweep names a cell's picture alike and the merge can require
//! exactly that name.

use super::ConfigRecord;
use std::collections::{HashMap, HashSet};

/// The longest stem, in bytes (a file name may have 255).
pub(crate) const STEM_MAX: usize = 64;

/// A file name part for a name (`sism:exact-union,horizon` →
/// `sism-exact-union-horizon`): ASCII letters and digits, each run of
/// anything else one `-`, none at either end.
pub(crate) fn file_part(name: &str) -> String {
    let mut out = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c);
        } else if !out.ends_with('-') && !out.is_empty() {
            out.push('-');
        }
    }
    out.trim_end_matches('-').to_owned()
}

/// A stem for each of `names`, in order: [`file_part`] cut to
/// [`STEM_MAX`] bytes (`fallback` when nothing is left), the later of two
/// alike (ignoring case) suffixed `-2`, `-3`, … Linear in the names: each
/// flattened name remembers the last suffix it was given.
pub(crate) fn stems(names: &[String], fallback: &str) -> Vec<String> {
    let mut taken: HashSet<String> = HashSet::with_capacity(names.len());
    let mut next: HashMap<String, usize> = HashMap::new();
    names
        .iter()
        .map(|name| {
            let mut base = file_part(name);
            base.truncate(STEM_MAX);
            let base = match base.trim_end_matches('-') {
                "" => fallback.to_owned(),
                b => b.to_owned(),
            };
            let key = base.to_ascii_lowercase();
            if taken.insert(key.clone()) {
                return base;
            }
            let k = next.entry(key).or_insert(2);
            loop {
                let candidate = format!("{base}-{k}");
                *k += 1;
                if taken.insert(candidate.to_ascii_lowercase()) {
                    return candidate;
                }
            }
        })
        .collect()
}

/// The file names of one sweep.
pub(crate) struct Names {
    scenes: Vec<String>,
    settings: Vec<String>,
}

impl Names {
    /// The stems of `config`'s scenes and settings.
    pub(crate) fn new(config: &ConfigRecord) -> Names {
        Names {
            scenes: stems(&config.scenes, "scene"),
            settings: stems(&config.settings, "setting"),
        }
    }

    /// Cell `index`'s picture, relative to the report's folder.
    pub(crate) fn picture(&self, index: usize) -> String {
        let n = self.settings.len().max(1);
        format!(
            "pictures/{}/{}.png",
            self.scenes[index / n],
            self.settings[index % n]
        )
    }

    /// Plot `what` of scene number `scene`, relative to the report's folder.
    pub(crate) fn plot(&self, scene: usize, what: &str) -> String {
        format!("plots/{}/{what}.svg", self.scenes[scene])
    }
}

/// The whole factor by which the frame (`side`²) is shrunk to a picture
/// of about `pictures` (the scene named `default`: twice that), never
/// larger than the frame.
pub(crate) fn picture_factor(side: u32, pictures: u32, scene: &str) -> u32 {
    let wanted = if scene == "default" {
        pictures.saturating_mul(2)
    } else {
        pictures
    };
    (side / wanted.clamp(1, side.max(1))).max(1)
}

/// The white gap between a picture's two halves, in pixels.
pub(crate) const GAP: u32 = 4;

/// The size of a cell's picture on scene `scene`: the shaded frame and
/// the error heat-map (with its legend) side by side, each shrunk by
/// [`picture_factor`].
pub(crate) fn picture_size(side: u32, pictures: u32, scene: &str) -> (u32, u32) {
    let f = picture_factor(side, pictures, scene);
    let (w, h) = crate::output::image::heat_map_size(side, side);
    let (s, w, h) = (side / f, w / f, h / f);
    (s + GAP + w, s.max(h))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_parts_are_plain() {
        assert_eq!(
            file_part("sism:exact-union,horizon"),
            "sism-exact-union-horizon"
        );
        assert_eq!(file_part("mc:16"), "mc-16");
        assert_eq!(file_part("several-objects"), "several-objects");
        assert_eq!(file_part("../x/ y"), "x-y");
    }

    #[test]
    fn stems_are_unique_and_short() {
        let names: Vec<String> = ["a b", "a-b", "A-B", "a-b-2", "", "…", &"x".repeat(300)]
            .iter()
            .map(|s| (*s).to_owned())
            .collect();
        let s = stems(&names, "scene");
        assert_eq!(
            s[..6],
            ["a-b", "a-b-2", "A-B-3", "a-b-2-2", "scene", "scene-2"]
        );
        assert_eq!(s[6], "x".repeat(STEM_MAX));
        let lower: HashSet<String> = s.iter().map(|x| x.to_ascii_lowercase()).collect();
        assert_eq!(lower.len(), s.len());
        // Many alike stay linear and unique.
        let many: Vec<String> = (0..20_000).map(|k| " ".repeat(k % 7) + "s").collect();
        let s = stems(&many, "scene");
        let set: HashSet<&String> = s.iter().collect();
        assert_eq!(set.len(), many.len());
    }

    #[test]
    fn picture_factors_stay_within_the_frame() {
        assert_eq!(picture_factor(256, 128, "contact"), 2);
        assert_eq!(picture_factor(256, 128, "default"), 1);
        assert_eq!(picture_factor(16, u32::MAX, "default"), 1);
        assert_eq!(picture_factor(16, u32::MAX, "x"), 1);
        assert_eq!(picture_factor(40, 16, "x"), 2);
        assert_eq!(picture_factor(40, 13, "x"), 3);
        assert_eq!(picture_factor(16, 1, "x"), 16);
        // Frame and heat-map (18 legend rows below, at least 64 wide)
        // side by side, 4 pixels apart.
        assert_eq!(picture_size(256, 128, "contact"), (128 + 4 + 128, 137));
        assert_eq!(picture_size(16, 16, "x"), (16 + 4 + 64, 34));
    }
}

//! `steadyray calibrate --motion --merge`: the mean of motion models of the same ladder and
//! grids (how the model shipped with `perceptual` is made); models of other grids and files
//! that cannot be read are clear errors.

mod scratch;
use scratch::scratch;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_steadyray");

fn merge(files: &[&Path], out: &Path) -> Output {
    let list: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
    Command::new(BIN)
        .args(["calibrate", "--motion", "--merge", &list.join(",")])
        .arg("--out")
        .arg(out)
        .output()
        .expect("the steadyray binary runs")
}

/// The shipped model, with every score `scale` times its own and another scene's name.
fn model(scene: &str, scale: f64) -> Value {
    let text = include_str!("../../control/models/default-motion.json");
    let mut model: Value = serde_json::from_str(text).unwrap();
    model["scene"] = scene.into();
    for row in model["scores"].as_array_mut().unwrap() {
        for cells in row.as_array_mut().unwrap() {
            for cell in cells.as_array_mut().unwrap() {
                *cell = (cell.as_f64().unwrap() * scale).into();
            }
        }
    }
    model
}

fn write(dir: &Path, name: &str, value: &Value) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_string(value).unwrap()).unwrap();
    path
}

#[test]
fn models_of_the_same_grids_merge_into_their_mean_and_others_are_refused() {
    let tmp = scratch("merge");
    let dir = tmp.path();
    let a = write(dir, "a.json", &model("a", 1.0));
    let b = write(dir, "b.json", &model("b", 3.0));
    let out = dir.join("mean.json");
    let merged = merge(&[&a, &b], &out);
    assert!(merged.status.success(), "{merged:?}");
    let mean: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(mean["scene"], "a+b");
    let (first, twice) = (
        &model("a", 1.0)["scores"][1][0][0],
        &mean["scores"][1][0][0],
    );
    let expected = 2.0 * first.as_f64().unwrap();
    assert!(
        (twice.as_f64().unwrap() - expected).abs() < 1e-12,
        "{twice} vs {expected}"
    );

    let mut other = model("c", 1.0);
    other["speeds_deg_s"][1] = 9.5.into();
    let c = write(dir, "c.json", &other);
    let refused = merge(&[&a, &c], &dir.join("refused.json"));
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success());
    assert!(err.contains("speeds") && err.contains("c.json"), "{err}");
    assert!(!dir.join("refused.json").exists());

    let missing = merge(&[&a, &dir.join("none.json")], &dir.join("x.json"));
    let err = String::from_utf8_lossy(&missing.stderr);
    assert!(
        !missing.status.success() && err.contains("cannot read"),
        "{err}"
    );
}

//! `hyst` on inputs and outputs a user gets wrong or cuts short: a closed pipe, repeated or
//! invalid options, duplicated keys, degenerate records. Each must end in a clear error (or, for
//! a closed pipe, quietly), never in a panic or a result computed from something other than what
//! was asked.

#[path = "support/cli.rs"]
mod cli;

use cli::{err, hyst, ok, tmp, write};
use std::process::{Command, Output, Stdio};

/// Plain Bouc-Wen parameters.
const BW: &str = r#"{"model": "bw", "k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1}"#;

/// A small displacement-driven record: two cycles of a stiff-then-yielding column.
fn column_record() -> String {
    let mut text = String::from("disp_mm,force_kN\n");
    let mut u = 0.0f64;
    let mut z = 0.0f64;
    for amplitude in [2.0, -2.0, 4.0, -4.0, 0.0] {
        while (amplitude - u).abs() > 1e-9 {
            let du = (amplitude - u).clamp(-0.1, 0.1);
            // Plain Bouc-Wen (n = 1, beta = gamma = 0.5, k0 = 6, alpha = 0.1) by small
            // explicit steps: any hysteretic loop does here.
            z += du * (1.0 - z.abs() * (0.5 * (du * z).signum() + 0.5));
            u += du;
            text += &format!("{u:.4},{:.5}\n", 0.6 * u + 5.4 * z);
        }
    }
    text
}

/// [`column_record`] with each force value rewritten by `force` (its text as written).
fn column_record_with_force(mut force: impl FnMut(f64) -> String) -> String {
    column_record()
        .lines()
        .enumerate()
        .map(|(i, l)| match (i, l.split_once(',')) {
            (0, _) | (_, None) => format!("{l}\n"),
            (_, Some((u, f))) => format!("{u},{}\n", force(f.parse().unwrap())),
        })
        .collect()
}

/// `hyst fit PATH --method lsq --json EXTRA...`: its NRMSE and its standard error.
fn lsq_fit(path: &str, extra: &[&str]) -> (f64, String) {
    let mut args = vec!["fit", path, "--method", "lsq", "--json"];
    args.extend_from_slice(extra);
    let out = ok(hyst(&args));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    (v["nrmse"].as_f64().unwrap(), cli::stderr(&out))
}

/// `hyst fit PATH --method lsq EXTRA... --out OUT`: the fit file it writes.
fn lsq_fit_file(path: &str, extra: &[&str], out: &str) -> serde_json::Value {
    let args = [&["fit", path, "--method", "lsq"], extra, &["--out", out]].concat();
    ok(hyst(&args));
    serde_json::from_str(&std::fs::read_to_string(out).unwrap()).unwrap()
}

/// The first `lines` lines of the thesis' Bouc-Wen example (`benches/baselines/bw_synthetic.csv`:
/// 500 kg, k = 6 kN/mm, F = t sin(2 pi t) kN at 500 Hz, its comment lines included) as `name`.
fn thesis_example(name: &str, lines: usize) -> String {
    let full = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../benches/baselines/bw_synthetic.csv"
    ))
    .unwrap();
    let head: String = full.lines().take(lines).map(|l| format!("{l}\n")).collect();
    write(name, &head)
}

/// Runs `hyst` with `args`, its standard output a pipe that nobody reads any more.
fn into_closed_pipe(args: &[&str]) -> Output {
    // A pipe whose reading end has gone: `true` held it and has exited.
    let mut reader = Command::new("true")
        .stdin(Stdio::piped())
        .spawn()
        .expect("`true` runs");
    let pipe = reader.stdin.take().expect("a pipe");
    reader.wait().expect("`true` exits");
    Command::new(env!("CARGO_BIN_EXE_hyst"))
        .args(args)
        .stdout(pipe)
        .stderr(Stdio::piped())
        .output()
        .expect("hyst runs")
}

/// `hyst params | head -1` and the like: the reader went away, which is not an error, and
/// certainly not a panic (`println!` panics on a closed pipe; every verb writes with `?`).
#[test]
fn a_closed_pipe_ends_quietly() {
    let data = write("column.csv", &column_record());
    let params = write("bw.json", BW);
    let table = cli::tmp("bw.bin");
    let table = table.to_str().unwrap();
    ok(hyst(&[
        "export", &params, "--format", "bin", "--out", table,
    ]));
    let cases: [&[&str]; 5] = [
        &["params"],
        &["fit", &data, "--method", "lsq"],
        &["fit", &data, "--method", "lsq", "--json"],
        &["table", "check", table],
        &["diagnose", &data, "--candidates", "pinching"],
    ];
    for args in cases {
        let out = into_closed_pipe(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        assert!(out.status.success(), "{args:?}: {stderr}");
    }
}

/// `hyst params` lines its columns up whatever the names: the descriptions start at one
/// character column on every line (asymmetry's long names and equations pushed them out).
#[test]
fn the_parameter_table_is_aligned() {
    let out = ok(hyst(&["params", "--model", "bwbn+asymmetry"]));
    let text = String::from_utf8(out.stdout).unwrap();
    assert_eq!(text.lines().count(), 20, "{text}");
    // Each line's description follows the off value and two spaces.
    let first = text.lines().next().unwrap();
    let column = first[..first.find("description").unwrap()].chars().count();
    for line in text.lines() {
        let before: String = line.chars().take(column).collect();
        assert!(before.ends_with("  "), "{line:?}");
        let rest: String = line.chars().skip(column).collect();
        assert!(!rest.starts_with(' '), "{line:?}");
    }
}

/// `hyst params --model phm-torsion` lists the rule coefficients of thesis ch. 5 (it was refused
/// as an unknown model base): the values are the thesis' (eq. 4, k_Tr1/k_T1 = 0.7513 mu_c^-0.786),
/// and a PHM file holding every listed coefficient at its listed value simulates as one holding
/// none.
#[test]
fn the_phm_coefficients_are_listed() {
    let out = ok(hyst(&["params", "--model", "phm-torsion"]));
    let text = String::from_utf8(out.stdout).unwrap();
    let table: Vec<(String, f64)> = text
        .lines()
        .skip_while(|l| !l.starts_with("name"))
        .skip(1)
        .map(|l| {
            let cells: Vec<&str> = l.split_whitespace().collect();
            (cells[0].to_string(), cells[2].parse().unwrap())
        })
        .collect();
    assert!(table.contains(&("eq4_a".into(), 0.7513)), "{text}");
    assert!(table.contains(&("eq4_b".into(), -0.786)), "{text}");
    let mut all: serde_json::Value = serde_json::from_str(PHM).unwrap();
    all["coefficients"] = table
        .iter()
        .map(|(n, v)| (n.clone(), serde_json::Value::from(*v)))
        .collect();
    let mut none = all.clone();
    none.as_object_mut().unwrap().remove("coefficients");
    let (all, none) = (all.to_string(), none.to_string());
    let twist = write(
        "listed-twist.csv",
        "twist (deg)\n0\n1\n3\n0\n-3\n0\n5\n-5\n0\n",
    );
    let run = |name: &str, text: &str| {
        ok(hyst(&["simulate", &twist, "--params", &write(name, text)])).stdout
    };
    assert_eq!(run("listed-all.json", &all), run("listed-none.json", &none));
    // The history reaches the rules: the file's own coefficients change the loop.
    assert_ne!(run("listed-own.json", PHM), run("listed-none.json", &none));
}

/// `--fix` beside `--params` must agree with the file: `diagnose --params fit.json --fix beta=3`
/// evaluated the file's set with beta replaced by 3, without a word. Agreeing values pass (the
/// fix then holds in the candidates' fits too).
#[test]
fn a_fix_that_contradicts_the_parameter_file_is_refused() {
    let record = write("fix-record.csv", &column_record());
    let params = write("fix-bw.json", BW);
    let diagnose = |fix: &str| hyst(&["diagnose", &record, "--params", &params, "--fix", fix]);
    let e = err(diagnose("beta=3"));
    assert!(
        e.contains(&format!(
            "--fix beta=3 contradicts {}: beta = 2 there",
            place(&params, BW, "2, \"gamma\"")
        )),
        "{e}"
    );
    ok(diagnose("beta=2"));
}

/// A key given twice in a JSON file is refused with its place: `serde_json` alone would keep the
/// last one, and `k0` would silently be 60.
#[test]
fn a_repeated_json_key_is_refused() {
    let history = write("history.csv", "displacement (mm)\n0\n1\n2\n");
    let params = write(
        "repeated.json",
        r#"{"model": "bw", "k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1, "k0": 60}"#,
    );
    let e = cli::err(hyst(&["simulate", &history, "--params", &params]));
    assert!(
        e.contains("repeated.json:1:") && e.contains("key 'k0' given twice"),
        "{e}"
    );
}

/// `--fix` given twice, or with a value the model refuses, is an error naming the parameter
/// and the rule (it was a start that "could not be simulated", or the last value won).
#[test]
fn fixed_values_are_checked_once_and_by_the_models_rules() {
    let data = write("column-fix.csv", &column_record());
    let fit = |fix: &[&str]| {
        let mut args = vec!["fit", data.as_str(), "--method", "lsq"];
        for f in fix {
            args.extend(["--fix", f]);
        }
        cli::err(hyst(&args))
    };
    let e = fit(&["alpha=0.1", "alpha=0.3"]);
    assert!(
        e.contains("`alpha` is fixed twice (to 0.1 and to 0.3)"),
        "{e}"
    );
    let e = fit(&["alpha=5"]);
    assert!(
        e.contains("cannot fix `alpha` to 5: alpha must lie in [0, 1]"),
        "{e}"
    );
    let e = fit(&["k0=0"]);
    assert!(
        e.contains("cannot fix `k0` to 0: k0 must be greater than zero"),
        "{e}"
    );
    let e = cli::err(hyst(&["diagnose", &data, "--fix", "n=-1"]));
    assert!(
        e.contains("cannot fix `n` to -1: n must be greater than zero"),
        "{e}"
    );
    // 1e400 parses as infinity: refused as what was written, not as "to inf".
    let e = fit(&["beta=1e400"]);
    assert!(
        e.contains("`beta=1e400`: the value is not a finite number"),
        "{e}"
    );
}

/// The first 2 s of the thesis' Bouc-Wen example (README: `--mass 500 --fix k0=6`): plain
/// Bouc-Wen has no energy limit, so a start that dissipates more than twice the record's work
/// is simulated (it was refused, and the fit failed), and the fit reaches the record.
#[test]
fn a_short_force_driven_record_fits_plain_bouc_wen() {
    let data = thesis_example("bw-short.csv", 1000);
    let out = ok(hyst(&[
        "fit", &data, "--mass", "500", "--fix", "k0=6", "--method", "lsq", "--json",
    ]));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v["nrmse"].as_f64().unwrap() < 1e-4, "{v}");
}

/// A negative mass or sample rate reaches the checks that name it; clap took `-5` for an option
/// and advised `-- -5`, which would pass it as the data file (found by review).
#[test]
fn negative_numbers_are_refused_by_what_they_mean() {
    let data = write("negative.csv", &column_record());
    let e = err(hyst(&["fit", &data, "--mass", "-5", "--method", "lsq"]));
    assert!(
        e.contains("the mass must be a positive number of kg, got -5"),
        "{e}"
    );
    let e = err(hyst(&[
        "fit",
        &data,
        "--sample-rate",
        "-3",
        "--method",
        "lsq",
    ]));
    assert!(
        e.contains("expected a positive finite sample rate, found -3 Hz"),
        "{e}"
    );
}

/// A record with nothing to fit (a force that is zero throughout, a displacement that never
/// moves), forces too large to square or scales that put a parameter beyond f64 is refused, where a fit "succeeded" with `k0` at
/// 1e-308 or an NRMSE of NaN.
#[test]
fn records_without_anything_to_fit_are_refused() {
    let rows = |f: &dyn Fn(usize) -> (f64, f64)| {
        let mut t = String::from("disp_mm,force_kN\n");
        for i in 0..20 {
            let (u, p) = f(i);
            t += &format!("{u},{p}\n");
        }
        t
    };
    let zero_force = write("zero-force.csv", &rows(&|i| ((i % 5) as f64, 0.0)));
    let e = cli::err(hyst(&["fit", &zero_force, "--method", "lsq"]));
    assert!(
        e.contains("zero-force.csv: expected the force to vary, found 0 kN in every sample"),
        "{e}"
    );
    let still = write("still.csv", &rows(&|i| (0.0, (i % 3) as f64)));
    let e = cli::err(hyst(&["diagnose", &still]));
    assert!(
        e.contains("expected the displacement to vary, found 0 mm in every sample"),
        "{e}"
    );
    let huge = write(
        "huge.csv",
        &rows(&|i| ((i % 5) as f64, 1e155 * (i % 5) as f64)),
    );
    let e = cli::err(hyst(&["fit", &huge, "--method", "lsq"]));
    assert!(e.contains("found values up to 4e155 kN"), "{e}");
    // Forces that vary but whose squares underflow to zero: the fit reported NRMSE 0 (found
    // by review).
    let tiny = write(
        "tiny-force.csv",
        &rows(&|i| ((i % 5) as f64, 1e-299 * (i % 5) as f64)),
    );
    let e = cli::err(hyst(&["fit", &tiny, "--method", "lsq"]));
    assert!(
        e.contains("expected forces whose squares do not underflow to zero, found values only up to 4e-299 kN"),
        "{e}"
    );
    // A column record scaled down: at 1e-50 its beta scales as up to 1e200 (displacement^-n,
    // n up to 4) and it fits; at 1e-160 beta overflows within its search range, and the fit
    // ended at NRMSE 0.22 (against 6e-8 at 1e-150) without a word.
    let scaled = |name: &str, by: f64| {
        let mut text = String::from("disp_mm,force_kN\n");
        for line in column_record().lines().skip(1) {
            let (u, f) = line.split_once(',').unwrap();
            let (u, f): (f64, f64) = (u.parse().unwrap(), f.parse().unwrap());
            text += &format!("{:e},{:e}\n", u * by, f * by);
        }
        write(name, &text)
    };
    ok(hyst(&[
        "fit",
        &scaled("small.csv", 1e-50),
        "--method",
        "lsq",
    ]));
    let e = cli::err(hyst(&[
        "fit",
        &scaled("tiny.csv", 1e-160),
        "--method",
        "lsq",
    ]));
    assert!(
        e.contains("put `beta` beyond the range of f64 (1e-308 to 1e308) within its search range (it scales as displacement^-n, at n = 4): rescale the record"),
        "{e}"
    );
}

/// A force-driven fit file carries the test's mass: `sensitivity` and `diagnose --params` read
/// it as `simulate` does (they refused the file without `--mass`, blaming `--forcing`).
#[test]
fn force_driven_fit_files_carry_their_mass_to_every_verb() {
    let data = thesis_example("bw-mass.csv", 600);
    let fit = cli::tmp("bw-mass-fit.json");
    let fit = fit.to_str().unwrap();
    ok(hyst(&[
        "fit", &data, "--mass", "500", "--fix", "k0=6", "--method", "lsq", "--out", fit,
    ]));
    let out = ok(hyst(&["sensitivity", &data, "--params", fit, "--json"]));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v.to_string().contains("\"xi\""), "{v}");
    let out = ok(hyst(&[
        "diagnose",
        &data,
        "--params",
        fit,
        "--candidates",
        "asymmetry",
        "--json",
    ]));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v["nrmse"].as_f64().unwrap() < 1e-4, "{v}");
    // Another mass is the user's to choose, but it is said (found by review: it replaced the
    // file's without a word).
    let other = ok(hyst(&["simulate", &data, "--params", fit, "--mass", "100"]));
    let notes = cli::stderr(&other);
    assert!(
        notes.contains("note: --mass 100 kg replaces the mass of") && notes.contains("(500 kg)"),
        "{notes}"
    );
    let same = ok(hyst(&["simulate", &data, "--params", fit, "--mass", "500"]));
    assert!(!cli::stderr(&same).contains("replaces the mass"));
}

/// A parameter set the record cannot be run with is an error naming the sample, not a table:
/// with `beta + gamma = -3` and n = 2, z runs off to infinity before u reaches
/// pi / (2 sqrt 3) = 0.91 mm (`dz/du = 1 + 3 z^2`), and the record goes to 4 mm.
/// `sensitivity` printed every error as 0 and ranked the parameters; `diagnose` blamed
/// "the given parameters, or ones next to them".
#[test]
fn parameters_the_record_cannot_run_are_refused_with_the_failing_sample() {
    let data = write("runaway-record.csv", &column_record());
    let params = write(
        "runaway.json",
        r#"{"model": "bw", "k0": 6, "alpha": 0.1, "n": 2, "beta": -2, "gamma": -1}"#,
    );
    let sample = |e: &str| {
        let at = e.find("step to sample ").expect("a failing sample");
        e[at..].split_whitespace().nth(3).map(str::to_string)
    };
    let mut numbers = Vec::new();
    for verb in ["sensitivity", "diagnose"] {
        let e = err(hyst(&[verb, &data, "--params", &params]));
        assert!(
            e.contains("runaway-record.csv")
                && e.contains("runaway.json")
                && e.contains("step to sample"),
            "{verb}: {e}"
        );
        numbers.push(sample(&e));
    }
    // `simulate` names the record and counts the samples as the others do (it counted from 1,
    // they from 0, and it named no file: found by review).
    let e = err(hyst(&["simulate", &data, "--params", &params]));
    assert!(e.contains("runaway-record.csv: step to sample"), "{e}");
    numbers.push(sample(&e));
    assert!(numbers.windows(2).all(|w| w[0] == w[1]), "{numbers:?}");
}

/// `sensitivity` sweeps what it says: fewer than three levels is an error (it was
/// quietly three), and a parameter at zero is swept over its fitting range, which the
/// output says, as it counts the changes that could not be simulated.
#[test]
fn sensitivity_says_what_it_swept() {
    let data = write("sweep-record.csv", &column_record());
    let params = write(
        "sweep.json",
        r#"{"model": "bw", "k0": 6, "alpha": 0, "n": 1, "beta": 0.5, "gamma": 0.5}"#,
    );
    let e = err(hyst(&[
        "sensitivity",
        &data,
        "--params",
        &params,
        "--levels",
        "2",
    ]));
    assert!(e.contains("at least 3 levels"), "{e}");
    let out = ok(hyst(&["sensitivity", &data, "--params", &params, "--json"]));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let alpha = v
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == "alpha")
        .unwrap();
    assert_eq!(alpha["of_range"], true, "{alpha}");
    // alpha < 0 is not a parameter set: the five negative changes of eleven.
    assert_eq!(alpha["not_simulated"], 5, "{alpha}");
    let text =
        String::from_utf8(ok(hyst(&["sensitivity", &data, "--params", &params])).stdout).unwrap();
    assert!(text.contains("fitting range"), "{text}");
    assert!(text.contains("not simulated"), "{text}");
}

/// A force-driven record needs the fit's damping: a file without `xi` is refused (it
/// was swept at a made-up 0.05), and a mass that is not positive names its place.
#[test]
fn force_driven_verbs_make_up_no_damping_and_place_a_bad_mass() {
    let data = thesis_example("bw-no-xi.csv", 600);
    let no_xi = write(
        "no-xi.json",
        r#"{"model": "bw", "k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1, "m": 500}"#,
    );
    for verb in ["sensitivity", "diagnose"] {
        let e = err(hyst(&[verb, &data, "--params", &no_xi]));
        assert!(
            e.contains("no `xi`") && e.contains("no-xi.json"),
            "{verb}: {e}"
        );
    }
    let bad_mass = write(
        "bad-mass.json",
        "{\"model\": \"bw\", \"k0\": 6, \"alpha\": 0.2, \"n\": 1.2, \"beta\": 2,\n \"gamma\": -1, \"xi\": 0.05, \"m\": -5}",
    );
    for verb in ["sensitivity", "diagnose", "simulate"] {
        let e = err(hyst(&[verb, &data, "--params", &bad_mass]));
        assert!(
            e.contains("bad-mass.json:2:") && e.contains("got -5"),
            "{verb}: {e}"
        );
    }
    // Positive but too small for the mass-normalised oscillator: the fit blamed k0 (found by
    // review).
    let e = err(hyst(&["fit", &data, "--mass", "1e-308", "--method", "lsq"]));
    assert!(
        e.contains("the mass of 1e-308 kg is too small for this record") && !e.contains("k0"),
        "{e}"
    );
    // Within f64 but far too fast to integrate: 1e-300 kg failed later as "model diverged".
    // 5e-4 is the thesis' 500 kg given in kN s^2/mm: a million times too light, the
    // oscillator turns 1000 times faster (over 100 radians a sample with the record's secant
    // stiffness, at least 2.3 kN/mm) and the first simulation ran out of sub-steps.
    for mass in ["1e-300", "5e-4"] {
        let e = err(hyst(&["fit", &data, "--mass", mass, "--method", "lsq"]));
        assert!(
            e.contains(&format!(
                "the mass of {mass} kg is too small for this record"
            )) && e.contains("secant stiffness")
                && e.contains("radians in one sample interval")
                && e.contains("the mass is in kg"),
            "{mass}: {e}"
        );
    }
    // The same mass from a parameter file, for every verb, judged by the record's secant
    // stiffness in all three.
    let light = write(
        "light.json",
        r#"{"model": "bw", "k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1, "xi": 0.05, "m": 1e-300}"#,
    );
    for verb in ["simulate", "diagnose", "sensitivity"] {
        let e = err(hyst(&[verb, &data, "--params", &light]));
        assert!(
            e.contains("the mass of 1e-300 kg is too small for this record")
                && e.contains("secant stiffness")
                && e.contains("radians in one sample interval"),
            "{verb}: {e}"
        );
    }
    // A fit's own file simulates: on the whole thesis record 0.0146 kg turns 25 radians a
    // sample with its secant stiffness of 2.3 kN/mm and 40 with k0 = 6, and simulate once
    // judged it by k0 and refused what fit had taken (found by review).
    let whole = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../benches/baselines/bw_synthetic.csv"
    );
    let fitted = tmp("light-fit.json").display().to_string();
    ok(hyst(&[
        "fit", whole, "--mass", "0.0146", "--fix", "k0=6", "--method", "lsq", "--out", &fitted,
    ]));
    ok(hyst(&["simulate", whole, "--params", &fitted]));
}

/// A value the device's arithmetic cannot hold is refused by name: Q15.16 holds +-32768 in
/// steps of 2^-16 = 1.5e-5, so beta = 2e-7 and gamma = 1e-7 round to zero (they were exported
/// as 0 and 0, a different model, with no word). `f32` holds them. (Out of range:
/// `export_table.rs`.)
#[test]
fn values_the_arithmetic_cannot_hold_are_refused_by_name() {
    let tiny = write(
        "tiny.json",
        &BW.replace(
            r#""beta": 2, "gamma": -1"#,
            r#""beta": 2e-7, "gamma": 1e-7"#,
        ),
    );
    let export = |file: &str, scalar: &str| {
        hyst(&[
            "export",
            file,
            "--format",
            "bin",
            "--scalar",
            scalar,
            "--out",
            cli::tmp("held.bin").to_str().unwrap(),
        ])
    };
    let e = err(export(&tiny, "q16"));
    assert!(
        e.contains("tiny.json: beta = 0.0000002 rounds to 0 in q16"),
        "{e}"
    );
    ok(export(&tiny, "f32"));
    // export has no --model to point to: the file must say.
    let bare = write("no-model.json", &BW.replace(r#""model": "bw", "#, ""));
    let e = err(export(&bare, "f32"));
    assert!(
        e.contains("no-model.json: no \"model\" key") && !e.contains("--model"),
        "{e}"
    );
}

/// A record the model cannot be run on from any start is an error naming the record and
/// the failing sample (it said only "check the fixed parameters and bounds", with nothing
/// fixed): here a displacement-driven column read as force-driven by `--mass`. At 500 kg and
/// 1 Hz the mass check refuses it first (62 radians a sample); at 2,200 kg (30) it fits, and
/// with k0 fixed at 600 kN/mm, 300 times its secant stiffness, no start can be simulated, and
/// the message points at what was fixed.
#[test]
fn a_fit_that_cannot_start_names_the_record_and_the_sample() {
    let data = write("column-as-forced.csv", &column_record());
    // A time column named and a sample rate that replaces it: two answers, refused (it took
    // the rate with a note).
    let e = err(hyst(&["fit", &data, "--time", "1", "--sample-rate", "1"]));
    assert!(e.contains("cannot be used with '--sample-rate"), "{e}");
    let e = err(hyst(&["fit", &data, "--mass", "500", "--sample-rate", "1"]));
    assert!(
        e.contains("column-as-forced.csv: the mass of 5e2 kg is too small for this record")
            && e.contains("6.244e1 radians in one sample interval"),
        "{e}"
    );
    let e = err(hyst(&[
        "fit",
        &data,
        "--mass",
        "2200",
        "--sample-rate",
        "1",
        "--fix",
        "k0=600",
    ]));
    assert!(
        e.contains("column-as-forced.csv: the model could not be simulated from any of its starts (at the first: step to sample")
            && e.contains("check the fixed parameters"),
        "{e}"
    );
}

/// A PHM file (phm_cli.rs's asymmetric column).
const PHM: &str = r#"{"model": "phm-torsion", "units": {"twist": "deg", "torque": "kN m"},
 "primary": {"positive": [[0.2, 100.0], [1.2, 160.0], [4.2, 172.0], [7.5, 150.0]],
             "negative": [[0.25, 110.0], [1.3, 158.0], [4.3, 166.0], [7.5, 140.0]]},
 "coefficients": {"eq2b_b": 0.38, "eq3b_b": 0.12, "eq4_a": 0.65, "eq5b_b": 0.85, "eq6_c": 0.95}}"#;

/// A parameter file that does not parse is reported as such, also with `--json` (which is
/// for PHM files): a truncated PHM file was answered "--json is for --model phm-torsion".
#[test]
fn a_truncated_parameter_file_is_reported_before_the_options() {
    let cut = write("cut-phm.json", &PHM[..60]);
    let twist = write("cut-twist.csv", "twist (deg)\n0\n1\n0\n");
    let e = err(hyst(&["simulate", &twist, "--params", &cut, "--json"]));
    assert!(
        e.contains("cut-phm.json:") && !e.contains("--json is for"),
        "{e}"
    );
}

/// Parameter and PHM files saved with a byte-order mark (Notepad's) read as without it: they
/// were refused as "not valid JSON ... at line 1 column 1". A Latin-1 byte is refused at its
/// line and column; it was "cannot read: stream did not contain valid UTF-8", with no place.
#[test]
fn parameter_files_with_a_bom_read_and_latin1_is_placed() {
    let bytes = |name: &str, b: &[u8]| {
        let p = cli::tmp(name);
        std::fs::write(&p, b).unwrap();
        p.to_str().unwrap().to_string()
    };
    let history = write("bom-history.csv", "displacement (mm)\n0\n1\n-1\n0\n");
    let simulate = |params: &str| ok(hyst(&["simulate", &history, "--params", params])).stdout;
    let bom = bytes("bom.json", &[b"\xef\xbb\xbf", BW.as_bytes()].concat());
    assert_eq!(simulate(&bom), simulate(&write("no-bom.json", BW)));
    let twist = write("bom-twist.csv", "twist (deg)\n0\n1\n0\n-1\n0\n");
    let phm = |params: &str| ok(hyst(&["simulate", &twist, "--params", params])).stdout;
    let phm_bom = bytes("bom-phm.json", &[b"\xef\xbb\xbf", PHM.as_bytes()].concat());
    assert_eq!(phm(&phm_bom), phm(&write("no-bom-phm.json", PHM)));
    let at = BW.find(r#""bw""#).unwrap() + 3;
    let mut latin1 = BW.as_bytes().to_vec();
    latin1.insert(at, 0xe9);
    let e = err(hyst(&[
        "simulate",
        &history,
        "--params",
        &bytes("latin1.json", &latin1),
    ]));
    assert!(
        e.contains(&format!("latin1.json:1:{}: byte 0xe9 is not UTF-8", at + 1)),
        "{e}"
    );
}

/// `export --history` drives the elements with the history's quantity: a twist history for
/// Bouc-Wen elements, or millimetres for the PHM, is refused (degrees were read as mm), and the
/// reader's notes are printed as by every other verb.
#[test]
fn export_histories_are_of_the_elements_quantity() {
    let bw = write("export-bw.json", BW);
    let phm = write("export-phm.json", PHM);
    let twist = write("twist.csv", "twist (deg)\n0\n1\n3\n0\n-3\n0\n");
    let mm = write("mm.csv", "displacement (mm)\n0\n1\n3\n0\n-3\n0\n");
    let plain = write("plain.csv", "disp\n0\n1\n3\n0\n-3\n0\n");
    let table = cli::tmp("export.bin");
    let table = table.to_str().unwrap();
    let export = |params: &str, history: &str| {
        hyst(&[
            "export",
            params,
            "--format",
            "bin",
            "--scalar",
            "f32",
            "--history",
            history,
            "--out",
            table,
        ])
    };
    let e = cli::err(export(&bw, &twist));
    assert!(
        e.contains("twist.csv: a twist history, but the table holds Bouc-Wen elements"),
        "{e}"
    );
    let e = cli::err(export(&phm, &mm));
    assert!(
        e.contains("mm.csv: a displacement history, but the table holds PHM elements"),
        "{e}"
    );
    let done = ok(export(&bw, &plain));
    let notes = cli::stderr(&done);
    assert!(
        notes.contains("note: column 'disp' states no unit: assumed mm"),
        "{notes}"
    );
}

/// A force-driven `simulate` prints the reader's notes, and blames a parameter the model refuses
/// on the parameter file, not on the record.
#[test]
fn force_driven_simulate_names_the_right_file() {
    let data = thesis_example("bw-sim.csv", 200);
    let with_xi = |xi: f64| {
        format!(
            r#"{{"model": "bw", "k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1, "m": 500, "xi": {xi}}}"#
        )
    };
    let bad = write("negative-xi.json", &with_xi(-0.5));
    let e = cli::err(hyst(&["simulate", &data, "--params", &bad]));
    assert!(
        e.contains(&format!(
            "{}: invalid parameters: xi must not be negative",
            place(&bad, &with_xi(-0.5), "-0.5")
        )),
        "{e}"
    );
    let good = write("xi.json", &with_xi(0.05));
    let done = ok(hyst(&[
        "simulate",
        &data,
        "--params",
        &good,
        "--skip-rows",
        "1",
    ]));
    let notes = cli::stderr(&done);
    assert!(notes.contains("skipped as asked"), "{notes}");
}

/// `export --name` must be usable in the language it is written for: a keyword gave a file that
/// does not compile (`pub static fn`, `uint8_t for[64]`).
#[test]
fn export_names_are_not_keywords() {
    let bw = write("keyword-bw.json", BW);
    let export =
        |format: &str, name: &str| hyst(&["export", &bw, "--format", format, "--name", name]);
    let e = cli::err(export("rust", "fn"));
    assert!(e.contains(r#"--name "fn" is a keyword of Rust"#), "{e}");
    let e = cli::err(export("c", "for"));
    assert!(e.contains(r#"--name "for" is a keyword of C"#), "{e}");
    // Each language's keywords only: `fn` names a C array, `for_table` either.
    ok(export("c", "fn"));
    ok(export("rust", "for_table"));
    // A binary table has no name: the option is refused, not ignored.
    let e = cli::err(export("bin", "columns"));
    assert!(e.contains("a binary table has no name"), "{e}");
}

/// NSGA-II's settings with another method are refused, not ignored (`--bits 8` with the
/// default `auto` ran auto and said nothing).
#[test]
fn evolutionary_settings_need_nsga2() {
    let data = write("column-evolution.csv", &column_record());
    for (flag, value) in [
        ("--population", "10"),
        ("--generations", "5"),
        ("--seed", "5"),
        ("--bits", "8"),
    ] {
        for method in ["auto", "lsq"] {
            let e = cli::err(hyst(&["fit", &data, "--method", method, flag, value]));
            assert!(
                e.contains(&format!(
                    "{flag} is a setting of NSGA-II, which method {method}"
                )),
                "{e}"
            );
        }
    }
}

/// `diagnose --candidates` weighs each effect once, and only effects the model lacks.
#[test]
fn candidates_are_distinct_effects_to_add() {
    let data = write("column-candidates.csv", &column_record());
    let e = cli::err(hyst(&[
        "diagnose",
        &data,
        "--candidates",
        "pinching,pinching",
    ]));
    assert!(
        e.contains("candidate effect `pinching` is given twice"),
        "{e}"
    );
    let e = cli::err(hyst(&[
        "diagnose",
        &data,
        "--model",
        "bw+pinching",
        "--candidates",
        "pinching",
    ]));
    assert!(
        e.contains("candidate effect `pinching` is already in the model bw+pinching"),
        "{e}"
    );
}

/// A parameter file's `"units"` are checked (both keys, known units, nothing else), and the
/// verbs that simulate in mm and kN refuse parameters stated in other units, which they read as
/// mm and kN before; `export` labels a device table with them, by symbol.
#[test]
fn parameter_units_are_checked_and_never_ignored() {
    let history = write("units-history.csv", "displacement (mm)\n0\n1\n2\n");
    let with_units = |name: &str, units: &str| {
        write(
            name,
            &BW.replace(
                r#""model": "bw","#,
                &format!(r#""model": "bw", "units": {units},"#),
            ),
        )
    };
    let simulate = |params: &str| hyst(&["simulate", &history, "--params", params]);
    let foreign = with_units("units-foreign.json", r#"{"foo": "bar"}"#);
    let e = cli::err(simulate(&foreign));
    assert!(e.contains(r#""units" has a key "foo""#), "{e}");
    let half = with_units("units-half.json", r#"{"displacement": "mm"}"#);
    let e = cli::err(hyst(&["export", &half, "--format", "bin"]));
    assert!(e.contains(r#""units" needs "force" as a string"#), "{e}");
    let wrong = with_units(
        "units-wrong.json",
        r#"{"displacement": "kN", "force": "kN"}"#,
    );
    let e = cli::err(simulate(&wrong));
    assert!(
        e.contains(r#""units"."displacement" is 'kN'; expected a length unit"#),
        "{e}"
    );
    let inches = with_units("units-in.json", r#"{"displacement": "in", "force": "kip"}"#);
    let e = cli::err(simulate(&inches));
    assert!(
        e.contains("parameters in in and kip, but hyst simulates in mm and kN"),
        "{e}"
    );
    let table = ok(hyst(&[
        "export", &inches, "--format", "bin", "--scalar", "f64",
    ]));
    assert!(
        cli::stderr(&table).contains("units in / kip"),
        "{}",
        cli::stderr(&table)
    );
    // A file without units in the same table takes them, and the note says so.
    let bare = write("units-none.json", BW);
    let table = ok(hyst(&[
        "export", &bare, &inches, "--format", "bin", "--scalar", "f64",
    ]));
    let notes = cli::stderr(&table);
    assert!(
        notes.contains("units-none.json states no units: the table takes in / kip from"),
        "{notes}"
    );
    let mm = with_units("units-mm.json", r#"{"displacement": "mm", "force": "kN"}"#);
    ok(simulate(&mm));
    // Units are compared as units: `MM` and `KN` (accepted in a header) are mm and kN, here
    // and in a table beside a file that spells them `mm` and `kN` (both were refused before).
    let upper = with_units(
        "units-upper.json",
        r#"{"displacement": "MM", "force": "KN"}"#,
    );
    ok(simulate(&upper));
    let table = ok(hyst(&[
        "export", &upper, &mm, "--format", "bin", "--scalar", "f64",
    ]));
    assert!(
        cli::stderr(&table).contains("units mm / kN, 2 elements"),
        "{}",
        cli::stderr(&table)
    );
}

/// `path:line:column` of the first occurrence of `needle` in `text` (column in bytes),
/// found by searching the text: the place an error about that value must name.
fn place(path: &str, text: &str, needle: &str) -> String {
    let at = text.find(needle).expect("needle in text");
    let line = text[..at].matches('\n').count() + 1;
    let column = text[..at].rsplit('\n').next().unwrap().len() + 1;
    format!("{path}:{line}:{column}")
}

/// An error about a value of a parameter or PHM file names its line and column, as a syntax
/// error does: before, it named the file alone, and in a file of two curves and a dozen
/// coefficients the reader had to find the value by its name.
#[test]
fn errors_in_json_values_name_their_line_and_column() {
    let bw = "{\n  \"model\": \"bw\",\n  \"k0\": 6.0,\n  \"alpha\": 5,\n  \"n\": 1.2, \"beta\": 2.0, \"gamma\": -1.0\n}\n";
    let misspelt = bw
        .replace("\"alpha\": 5", "\"alpha\": 0.5")
        .replace("-1.0\n", "-1.0, \"dlta\": 1\n");
    let phm = "{\n  \"model\": \"phm-torsion\",\n  \"primary\": {\n    \"positive\": [[0.21, 105.0], [1.45, 168.0], [1.0, 172.0], [8.5, 140.0]]\n  },\n  \"coefficients\": {\"eq4_a\": 0.7513,\n    \"cycle_band\": 0.05}\n}\n";
    let band = phm
        .replace("[1.0, 172.0]", "[4.0, 172.0]")
        .replace("0.05}", "-5}");
    let history = write("history.csv", "displacement (mm)\n0\n1\n2\n");
    let twist = write("twist.csv", "twist (deg)\n0\n1\n2\n");
    // (file, its text, a record it simulates, where the value starts, the error)
    let cases = [
        (
            "alpha5.json",
            bw.to_string(),
            &history,
            "5,",
            "alpha must lie in [0, 1]",
        ),
        (
            "dlta.json",
            misspelt,
            &history,
            "1\n}",
            "\"dlta\" is not a parameter",
        ),
        (
            "point2.json",
            phm.to_string(),
            &twist,
            "[1.0, 172.0]",
            "positive primary curve, point 2: twists must increase",
        ),
        (
            "band.json",
            band,
            &twist,
            "-5}",
            "cycle_band must lie in [0, 1]",
        ),
    ];
    for (name, text, record, value, message) in cases {
        let file = write(name, &text);
        let want = format!("{}: {message}", place(&file, &text, value));
        for verb in [
            &["simulate", record, "--params", &file][..],
            &["export", "--format", "rust", &file],
        ] {
            let e = cli::err(hyst(verb));
            assert!(e.contains(&want), "{verb:?}: {e}");
        }
    }
}

/// An output path that is one of the inputs, another output, in a folder that does not exist,
/// or a folder, is refused before any work, and the input is left as it was (found by review: `--out` equal to
/// the record replaced the only copy of a lab record, and a missing folder lost a finished run).
#[test]
fn an_output_that_would_overwrite_an_input_is_refused_first() {
    let record = write("keep.csv", &column_record());
    let params = write("keep.json", BW);
    let e = err(hyst(&[
        "simulate", &record, "--params", &params, "--out", &record,
    ]));
    assert!(
        e.contains(&format!("--out {record}: that is the input {record}")),
        "{e}"
    );
    assert_eq!(std::fs::read_to_string(&record).unwrap(), column_record());
    // The same file under a second name (a hard link) is the same input.
    let link = cli::tmp("keep-link.csv");
    std::fs::remove_file(&link).ok();
    std::fs::hard_link(&record, &link).unwrap();
    let link = link.to_str().unwrap();
    let e = err(hyst(&[
        "simulate", &record, "--params", &params, "--out", link,
    ]));
    assert!(
        e.contains(&format!("--out {link}: that is the input {record}")),
        "{e}"
    );
    assert_eq!(std::fs::read_to_string(&record).unwrap(), column_record());
    let fit = err(hyst(&[
        "fit", &record, "--model", "bw", "--params", &params, "--out", &params,
    ]));
    assert!(fit.contains("that is the input"), "{fit}");
    assert_eq!(std::fs::read_to_string(&params).unwrap(), BW);
    let out = cli::tmp("twice.csv");
    let out = out.to_str().unwrap();
    let e = err(hyst(&[
        "simulate", &record, "--params", &params, "--out", out, "--plot", out,
    ]));
    assert!(e.contains("--out writes the same file"), "{e}");
    let missing = cli::tmp("no-such-folder").join("report.html");
    let missing = missing.to_str().unwrap();
    let e = err(hyst(&[
        "discover", &record, "--model", "bw", "--report", missing,
    ]));
    assert!(e.contains("does not exist"), "{e}");
    // A folder as the file: refused before the work, which it used to finish and then lose.
    let folder = cli::tmp("a-folder");
    std::fs::create_dir_all(&folder).unwrap();
    let folder = folder.to_str().unwrap();
    let e = err(hyst(&[
        "discover", &record, "--model", "bw", "--report", folder,
    ]));
    assert!(
        e.contains(&format!(
            "--report {folder}: that is a folder; give a file name"
        )),
        "{e}"
    );
}

/// A force-driven record with one row missing is refused at the gap, against the record's
/// typical step (the check compared with the mean step, which the gap shifts, and blamed the
/// second sample: found by review).
#[test]
fn a_missing_row_of_a_force_driven_record_is_placed() {
    let full = thesis_example("gap-full.csv", 400);
    let text: String = std::fs::read_to_string(&full)
        .unwrap()
        .lines()
        .enumerate()
        // Line 205 holds sample 201 (t = 0.4 s): drop it.
        .filter(|(k, _)| *k + 1 != 205)
        .map(|(_, l)| format!("{l}\n"))
        .collect();
    let gap = write("gap.csv", &text);
    let e = err(hyst(&["fit", &gap, "--model", "bw", "--mass", "500"]));
    assert!(
        e.contains("gap.csv: sample 201 is 0.004")
            && e.contains("where the record's steps are 0.002"),
        "{e}"
    );
}

/// A PHM file given where Bouc-Wen parameters are expected, or a misspelt model, is reported as
/// such at its `"model"` key (both read as `parameter "coefficients" must be a number`, the first
/// key in alphabetical order that was not a number: found by review).
#[test]
fn a_phm_file_or_a_misspelt_model_is_named_at_the_model_key() {
    let data = write("phm-record.csv", &column_record());
    let phm = write(
        "column-phm.json",
        "{\n  \"model\": \"phm-torsion\",\n  \"coefficients\": {}\n}\n",
    );
    for verb in ["sensitivity", "diagnose"] {
        let e = err(hyst(&[verb, &data, "--params", &phm]));
        assert!(
            e.contains("column-phm.json:2:12: a PHM file (model phm-torsion)"),
            "{verb}: {e}"
        );
    }
    let typo = write(
        "typo.json",
        "{\n  \"model\": \"bwbm\",\n  \"coefficients\": {}\n}\n",
    );
    let e = err(hyst(&["sensitivity", &data, "--params", &typo]));
    assert!(e.contains("typo.json:2:12: key \"model\""), "{e}");
}

/// A parameter set that is valid as written but overflows once scaled to the record (n = 1000
/// raises the displacement scale to the 1000th power in beta's unit) says so, instead of calling
/// the file's finite beta "not finite" (found by review).
#[test]
fn a_set_that_cannot_be_scaled_to_the_record_says_so() {
    // The column record with ten times the displacement: its scale is then well above 2 mm.
    let wide: String = column_record()
        .lines()
        .map(|l| {
            let row = l
                .split_once(',')
                .and_then(|(u, f)| Some((u.parse::<f64>().ok()?, f)));
            match row {
                Some((u, f)) => format!("{},{f}\n", 10.0 * u),
                None => format!("{l}\n"),
            }
        })
        .collect();
    let data = write("scaled-record.csv", &wide);
    let params = write(
        "n1000.json",
        r#"{"model": "bw", "k0": 6, "alpha": 0.2, "n": 1000, "beta": 2, "gamma": -1}"#,
    );
    for verb in ["diagnose", "sensitivity"] {
        let e = err(hyst(&[verb, &data, "--params", &params]));
        assert!(
            e.contains("valid as written, but not once scaled to the displacement and force of")
                && e.contains("scaled-record.csv"),
            "{verb}: {e}"
        );
    }
}

/// A torque unit beside a length (`force (kNm)`, a misspelt kN) names both columns and their
/// units, and how to read the column as a force (the message named neither: found by review).
#[test]
fn a_torque_unit_beside_a_length_names_the_columns() {
    let text = column_record().replacen("disp_mm,force_kN", "displacement (mm),force (kNm)", 1);
    let data = write("knm.csv", &text);
    let params = write("knm.json", BW);
    for args in [
        vec!["simulate", &data, "--params", &params],
        vec!["fit", &data, "--model", "bw"],
    ] {
        let e = err(hyst(&args));
        assert!(
            e.contains("column 'displacement (mm)' is a length (mm), column 'force (kNm)' is a torque (kN m)")
                && e.contains("--force COLUMN:kN"),
            "{args:?}: {e}"
        );
    }
    // And that reading works.
    ok(hyst(&[
        "simulate", &data, "--params", &params, "--force", "2:kN",
    ]));
}

/// Progress reaches a log: with standard error a file or a pipe (here: a pipe), a long run
/// writes plain lines, each stage and the ladder's rungs, stamped with the time. There was no
/// spinner and no line at all before (a discovery of 13 minutes said nothing until it ended:
/// found by review).
#[test]
fn progress_reaches_a_log_as_plain_lines() {
    let data = write("progress.csv", &column_record());
    let o = ok(hyst(&["discover", &data, "--model", "bw"]));
    let log = cli::stderr(&o);
    let lines: Vec<&str> = log.lines().collect();
    assert!(
        lines.iter().any(|l| l.starts_with("discover from bw [")
            && l.ends_with("] weighing the candidate effects")),
        "{log}"
    );
    assert!(
        lines
            .iter()
            .any(|l| l.contains("] bw ") && l.contains("NRMSE")),
        "{log}"
    );
    assert!(!log.contains('\r') && !log.contains('\u{1b}'), "{log:?}");
    // A JSON run keeps standard error for errors.
    let o = ok(hyst(&["discover", &data, "--model", "bw", "--json"]));
    assert_eq!(cli::stderr(&o), "");
}

/// `--fix` of a candidate effect's parameter (`diagnose --model bw --fix zeta0=0.3`) holds it
/// when the effect is added, where it was refused as "no such parameter"; a value the effect
/// refuses is named before any fit, and so is a parameter of an effect that is not weighed.
#[test]
fn a_candidate_effect_parameter_is_held_when_it_is_added() {
    let data = write("column-held.csv", &column_record());
    let added = |fixes: &[&str]| -> (u64, String) {
        let mut args = vec!["diagnose", &data, "--candidates", "pinching", "--json"];
        for f in fixes {
            args.extend(["--fix", f]);
        }
        let out = ok(hyst(&args));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["model"], "bw", "{v}");
        assert_eq!(v["suspects"][0]["effect"], "pinching", "{v}");
        let evidence = v["suspects"][0]["evidence"].as_str().unwrap().to_string();
        (
            v["suspects"][0]["added_parameters"].as_u64().unwrap(),
            evidence,
        )
    };
    let (six, words) = added(&[]);
    assert_eq!(six, 6);
    assert!(
        words.starts_with("Adding pinching (6 parameters) "),
        "{words}"
    );
    let (five, words) = added(&["zeta0=0.3"]);
    assert_eq!(five, 5);
    assert!(
        words.starts_with("Adding pinching (5 parameters, with zeta0 = 0.3 held) "),
        "{words}"
    );
    let (four, words) = added(&["zeta0=0.3", "lambda=0.5", "alpha=0.1"]);
    assert_eq!(four, 4);
    assert!(
        words
            .starts_with("Adding pinching (4 parameters, with zeta0 = 0.3 and lambda = 0.5 held) "),
        "{words}"
    );

    let e = err(hyst(&[
        "diagnose",
        &data,
        "--candidates",
        "pinching",
        "--fix",
        "zeta0=1.5",
    ]));
    assert!(
        e.contains("error: --fix for the candidate pinching: cannot fix `zeta0` to 1.5"),
        "{e}"
    );
    let e = err(hyst(&[
        "discover",
        &data,
        "--candidates",
        "strength-degradation",
        "--fix",
        "zeta0=0.3",
    ]));
    assert!(
        e.contains(
            "cannot fix `zeta0`: it is a parameter of pinching, which is neither in the model bw \
             nor among the candidate effects (strength-degradation)"
        ),
        "{e}"
    );
}

/// Found by review: settings so large that the run cannot hold them crashed (`--levels
/// 2305843009213693952`: a capacity overflow; `--population 4000000000`: an allocation of
/// 192 GB); they are refused with the limit.
#[test]
fn settings_beyond_memory_are_refused_with_their_limit() {
    let data = write("limits.csv", &column_record());
    let params = write("limits.json", BW);
    let e = cli::err(hyst(&[
        "sensitivity",
        &data,
        "--params",
        &params,
        "--levels",
        "2305843009213693952",
    ]));
    assert!(
        e.contains("the sweep takes at most 1001 levels (steps of 0.1%), got 2305843009213693952"),
        "{e}"
    );
    let e = cli::err(hyst(&[
        "fit",
        &data,
        "--method",
        "nsga2",
        "--population",
        "4000000000",
        "--generations",
        "1",
    ]));
    assert!(
        e.contains("NSGA-II setting `population` = 4000000000: expected 2 to 10,000"),
        "{e}"
    );
}

/// Found by review: `export --history` drove a table stated in m and N with the history's
/// millimetres as metres (the precision was measured at 1000 times the amplitude), and a
/// history that does not move reported a perfect precision over nothing.
#[test]
fn export_histories_are_read_in_the_tables_units() {
    let in_mm = write("export-mm.json", BW);
    let in_m = write(
        "export-m.json",
        &BW.replace('}', r#", "units": {"displacement": "m", "force": "kN"}}"#),
    );
    let history = write(
        "export-history.csv",
        "displacement (mm)\n0\n1\n3\n0\n-3\n0\n3\n",
    );
    let table = cli::tmp("export-units.bin");
    let peak = |params: &str| {
        let o = ok(hyst(&[
            "export",
            params,
            "--format",
            "bin",
            "--scalar",
            "f32",
            "--history",
            &history,
            "--out",
            table.to_str().unwrap(),
        ]));
        // The row of element 0: index, file, peak force, ...
        let text = cli::stderr(&o);
        let row = text
            .lines()
            .find(|l| l.trim_start().starts_with("0 "))
            .unwrap_or_else(|| panic!("{text}"));
        row.split_whitespace()
            .nth(2)
            .unwrap()
            .parse::<f64>()
            .unwrap()
    };
    // Zu = 1 unit of displacement. In mm the element yields well before 3 mm (alpha k0 u +
    // (1 - alpha) k0 Zu = 8.4 kN at most); in m, 0.003 m is far below Zu = 1 m and it stays
    // elastic: k0 u = 0.018 kN.
    let (mm, m) = (peak(&in_mm), peak(&in_m));
    assert!(mm > 4.0 && mm < 8.4, "{mm}");
    assert!((m / 0.018 - 1.0).abs() < 0.01, "{m}");
    let one = write("export-one.csv", "displacement (mm)\n2.5\n");
    let e = cli::err(hyst(&[
        "export",
        &in_mm,
        "--format",
        "bin",
        "--history",
        &one,
        "--out",
        table.to_str().unwrap(),
    ]));
    assert!(
        e.contains("export-one.csv: expected a history that moves, found 1 sample at one place: nothing to compare"),
        "{e}"
    );
}

/// Found by review: the asymmetries' range was given as [0, 1] while -0.99 was accepted, and a
/// pinching width of zero "must be greater than zero" while -0.1 was accepted.
#[test]
fn range_messages_state_the_range_that_is_checked() {
    let data = write("ranges.csv", &column_record());
    let e = cli::err(hyst(&[
        "fit",
        &data,
        "--model",
        "bw+asymmetry",
        "--fix",
        "asym_strength=1",
    ]));
    assert!(e.contains("asym_strength must lie in (-1, 1)"), "{e}");
    let e = cli::err(hyst(&[
        "fit",
        &data,
        "--model",
        "bw+pinching",
        "--fix",
        "psi0=0",
    ]));
    assert!(e.contains("psi0 must not be zero"), "{e}");
}

/// `--subtract` takes a known zero offset off a channel as the record is read, says so, adds up
/// two given for one channel, and is refused where it cannot mean anything: a channel the record
/// lacks, a value that is not a number. A fit of a record with a force offset taken off is the
/// fit of the record without it.
#[test]
fn subtract_takes_a_zero_offset_off_a_channel_and_says_so() {
    let history = write("shifted.csv", "displacement (mm)\n0.5\n1.0\n1.5\n0.5\n");
    let params = write("bw.json", BW);
    let simulate = |subtract: &[&str]| {
        let mut args = vec!["simulate", &history, "--params", &params];
        for s in subtract {
            args.extend(["--subtract", s]);
        }
        hyst(&args)
    };
    // The displacement column `simulate` wrote.
    let written = |out: &Output| -> Vec<f64> {
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .skip(1)
            .map(|l| l.split(',').next().unwrap().parse().unwrap())
            .collect()
    };
    let out = ok(simulate(&["displacement=0.5"]));
    assert_eq!(written(&out), [0.0, 0.5, 1.0, 0.0]);
    let note = cli::stderr(&out);
    assert!(
        note.contains("0.5 mm subtracted from every sample"),
        "{note}"
    );

    let e = err(simulate(&["force=1"]));
    assert!(
        e.contains("shifted.csv") && e.contains("the record has no force"),
        "{e}"
    );
    // Two for one channel are both taken off, each said.
    let out = ok(simulate(&["displacement=0.5", "displacement=0.25"]));
    assert_eq!(written(&out), [-0.25, 0.25, 0.75, -0.25]);
    assert_eq!(
        cli::stderr(&out)
            .matches("subtracted from every sample")
            .count(),
        2
    );
    for bad in [
        "rotation=1",
        "force",
        "force=inf",
        "force=x",
        "force=1..",
        "force=1..x",
    ] {
        let e = err(simulate(&[bad]));
        assert!(e.contains(bad), "{bad}: {e}");
    }

    // The same record with 0.7 kN added to every force sample, fitted with it taken off.
    let offset = column_record_with_force(|f| format!("{:.5}", f + 0.7));
    let fit_nrmse = |path: &str, extra: &[&str]| lsq_fit(path, extra).0;
    let clean_nrmse = fit_nrmse(&write("clean.csv", &column_record()), &[]);
    let offset_path = write("offset.csv", &offset);
    let with_offset = fit_nrmse(&offset_path, &[]);
    let taken_off = fit_nrmse(&offset_path, &["--subtract", "force=0.7"]);
    // An offset that swamps the values is named as the cause, written as the shortest number.
    let e = err(hyst(&[
        "fit",
        &offset_path,
        "--method",
        "lsq",
        "--subtract",
        "force=1e16",
    ]));
    assert!(
        e.contains("an offset of 1e16 kN to subtract from column")
            && e.contains("is more than 1e6 times its largest value"),
        "{e}"
    );
    // Measured: 0.0013 clean, 0.129 with the offset, 0.0019 with it taken off (the force
    // column rounded to 5 decimals after adding 0.7, and least squares from one start lands
    // elsewhere on this short record's flat valley: beta = gamma there).
    assert!(
        with_offset > 20.0 * clean_nrmse,
        "{with_offset} {clean_nrmse}"
    );
    assert!(taken_off < 2.0 * clean_nrmse, "{taken_off} {clean_nrmse}");
    // The fit file says what was taken off, for a later `simulate` or `diagnose --params`.
    let out = tmp("offset-fit.json");
    let out = out.to_str().unwrap();
    let file = lsq_fit_file(
        &offset_path,
        &["--subtract", "force=0.7", "--negate", "displacement"],
        out,
    );
    assert_eq!(file["fit"]["subtract"]["force"], 0.7, "{file}");
    assert_eq!(file["fit"]["negate"][0], "displacement", "{file}");
    // The verbs that line the fit up with its record say which of those options they are
    // not given again, one note each, and say nothing once both are given.
    for verb in ["diagnose", "sensitivity"] {
        let mut args = vec![verb, &offset_path, "--params", out];
        if verb == "diagnose" {
            args.extend(["--candidates", "asymmetry"]);
        }
        let note = cli::stderr(&ok(hyst(
            &[&args[..], &["--negate", "displacement"]].concat(),
        )));
        let unrepeated: Vec<&str> = note
            .lines()
            .filter(|l| l.contains("is not given here"))
            .collect();
        assert_eq!(unrepeated.len(), 1, "{verb}: {note}");
        assert!(
            unrepeated[0].contains("read with `--subtract force=0.7`"),
            "{verb}: {note}"
        );
        let both = [
            &args[..],
            &["--negate", "displacement", "--subtract", "force=0.7"],
        ]
        .concat();
        let note = cli::stderr(&ok(hyst(&both)));
        assert!(!note.contains("is not given here"), "{verb}: {note}");
    }
}

/// A load cell whose zero drifts, as `hyst diagnose` names it: `--subtract force=FIRST..LAST`
/// takes a line in the sample number off the force, says so, and the fit is that of the record
/// without the drift; the fit file records the line, and a later command that takes the same
/// line off in two parts (a constant, then what is left) is not told it differs.
#[test]
fn subtract_takes_a_drifting_zero_off_as_a_line() {
    let n = column_record().lines().count() - 1;
    let mut k = 0;
    let drifted = column_record_with_force(|f| {
        let drift = 0.2 + 0.7 * k as f64 / (n - 1) as f64;
        k += 1;
        format!("{:.5}", f + drift)
    });
    let clean_nrmse = lsq_fit(&write("undrifted.csv", &column_record()), &[]).0;
    let path = write("drifted.csv", &drifted);
    let as_read = lsq_fit(&path, &[]).0;
    let (taken_off, note) = lsq_fit(&path, &["--subtract", "force=0.2..0.9"]);
    assert!(
        note.contains(
            "column 'force_kN': a line from 0.2 kN at the first sample to 0.9 kN at the last \
             subtracted from its samples"
        ),
        "{note}"
    );
    // The force column rounded to 5 decimals after adding the drift, as the constant offset
    // of the test above; there 0.0013 clean and 0.0019 taken off.
    assert!(as_read > 20.0 * clean_nrmse, "{as_read} {clean_nrmse}");
    assert!(taken_off < 2.0 * clean_nrmse, "{taken_off} {clean_nrmse}");
    let out = tmp("drift-fit.json");
    let out = out.to_str().unwrap();
    let file = lsq_fit_file(&path, &["--subtract", "force=0.2..0.9"], out);
    assert_eq!(
        file["fit"]["subtract"]["force"],
        serde_json::json!([0.2, 0.9]),
        "{file}"
    );
    // The fitted set on the record read three ways: the line, the line in two parts (the same
    // record to rounding; a fit from one start can land elsewhere on this record's flat valley,
    // so the set is held fixed), the constant part alone.
    let diagnose = |subtract: &[&str]| {
        let mut args = vec![
            "diagnose",
            &path,
            "--params",
            out,
            "--candidates",
            "asymmetry",
            "--json",
        ];
        for s in subtract {
            args.extend(["--subtract", s]);
        }
        let o = ok(hyst(&args));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        (v["nrmse"].as_f64().unwrap(), cli::stderr(&o))
    };
    let (whole, note) = diagnose(&["force=0.2..0.9"]);
    assert!(!note.contains("was made on a record read with"), "{note}");
    let (in_two, note) = diagnose(&["force=0.2", "force=0..0.7"]);
    assert!(!note.contains("was made on a record read with"), "{note}");
    assert!((in_two - whole).abs() < 1e-9 * whole, "{in_two} {whole}");
    let (part, note) = diagnose(&["force=0.2"]);
    assert!(
        note.contains(
            "read with `--subtract force=0.2..0.9`; this command gives `--subtract force=0.2` \
             instead"
        ),
        "{note}"
    );
    assert!(part > 20.0 * whole, "{part} {whole}");
    // An option the fit was made without is said too (found by review).
    let plain = tmp("plain-fit.json");
    let plain = plain.to_str().unwrap();
    lsq_fit_file(&path, &[], plain);
    let note = cli::stderr(&ok(hyst(&[
        "diagnose",
        &path,
        "--params",
        plain,
        "--candidates",
        "asymmetry",
        "--subtract",
        "force=0.2..0.9",
    ])));
    assert!(
        note.contains("read without `--subtract force=0.2..0.9`, which this command gives"),
        "{note}"
    );
    // `simulate`, which draws a fit over its record, says so too (found by review).
    let note = cli::stderr(&ok(hyst(&["simulate", &path, "--params", out])));
    assert!(
        note.contains("read with `--subtract force=0.2..0.9`, which is not given here"),
        "{note}"
    );
}

/// `--lag` realigns a force read a sample late (as `hyst diagnose` names it) as the record is
/// read, says so, is recorded in the fit file as the force's lag whichever channel was named,
/// and is refused where it cannot mean anything.
#[test]
fn lag_realigns_a_channel_read_out_of_step_and_says_so() {
    let clean = column_record();
    let rows: Vec<&str> = clean.lines().collect();
    // The force column one sample late: each row's force is the row before's.
    let mut late = format!("{}\n", rows[0]);
    for k in 1..rows.len() {
        let u = rows[k].split(',').next().unwrap();
        let f = rows[k.saturating_sub(1).max(1)].split(',').nth(1).unwrap();
        late += &format!("{u},{f}\n");
    }
    let clean_nrmse = lsq_fit(&write("in-step.csv", &clean), &[]).0;
    let late_path = write("late.csv", &late);
    let as_read = lsq_fit(&late_path, &[]).0;
    let (realigned, note) = lsq_fit(&late_path, &["--lag", "force=1"]);
    assert!(
        note.contains("column 'force_kN' read 1 sample late")
            && note.contains("its first 1 sample and the last 1 of 'disp_mm' dropped"),
        "{note}"
    );
    // Measured: 0.00134 in step, 0.0266 one sample late, 0.00134 realigned.
    assert!(as_read > 10.0 * clean_nrmse, "{as_read} {clean_nrmse}");
    assert!(realigned < 2.0 * clean_nrmse, "{realigned} {clean_nrmse}");
    // The displacement read a sample early is the same realignment, to the last bit.
    let (same, _) = lsq_fit(&late_path, &["--lag", "displacement=-1"]);
    assert_eq!(same, realigned);

    let out = tmp("late-fit.json");
    let out = out.to_str().unwrap();
    let file = lsq_fit_file(&late_path, &["--lag", "displacement=-1"], out);
    assert_eq!(file["fit"]["lag"]["force"], 1, "{file}");
    let diagnose_with = |params: &str, extra: &[&str]| {
        let args = [
            &[
                "diagnose",
                &late_path,
                "--params",
                params,
                "--candidates",
                "asymmetry",
            ],
            extra,
        ]
        .concat();
        cli::stderr(&ok(hyst(&args)))
    };
    let diagnose = |extra: &[&str]| diagnose_with(out, extra);
    let note = diagnose(&[]);
    assert!(
        note.contains("read with `--lag force=1`, which is not given here"),
        "{note}"
    );
    let note = diagnose(&["--lag", "force=2"]);
    assert!(
        note.contains("read with `--lag force=1`; this command gives `--lag force=2` instead"),
        "{note}"
    );
    assert!(!diagnose(&["--lag", "force=1"]).contains("--lag"));
    // A fit file edited by hand: a lag of 1.0 is whole; two channels are not one lag.
    let edited = |lag: &str| {
        let text = std::fs::read_to_string(out).unwrap().replace(
            "\"lag\": {\n      \"force\": 1\n    }",
            &format!("\"lag\": {lag}"),
        );
        assert!(text.contains(lag), "{text}");
        write("edited-fit.json", &text)
    };
    let file = edited("{\"force\": 1.0}");
    let note = diagnose_with(&file, &["--lag", "force=1"]);
    assert!(!note.contains("--lag"), "{note}");
    let file = edited("{\"force\": 2, \"displacement\": 1}");
    let note = diagnose_with(&file, &[]);
    assert!(
        note.contains("is {\"displacement\":1,\"force\":2}, not an object of one channel's lag"),
        "{note}"
    );

    let samples = rows.len() - 1;
    let e = err(hyst(&[
        "fit",
        &late_path,
        "--lag",
        &format!("force={samples}"),
    ]));
    assert!(
        e.contains("late.csv")
            && e.contains(&format!(
                "a lag of {samples} samples between 'force_kN' and 'disp_mm' leaves fewer than 2 \
                 of the record's {samples} samples: expected a lag of at most {}",
                samples - 2
            )),
        "{e}"
    );
    let history = write("no-force.csv", "displacement (mm)\n0.5\n1.0\n1.5\n");
    let params = write("bw.json", BW);
    for (lag, said) in [
        ("force=1", "the force against the displacement"),
        ("displacement=1", "the displacement against the force"),
    ] {
        let e = err(hyst(&[
            "simulate", &history, "--params", &params, "--lag", lag,
        ]));
        assert!(
            e.contains("no-force.csv")
                && e.contains(&format!("cannot realign {said}: the record has no force")),
            "{e}"
        );
    }
    for bad in ["force=1.5", "rotation=1", "force", "force=x"] {
        let e = err(hyst(&["fit", &late_path, "--lag", bad]));
        assert!(e.contains(bad), "{bad}: {e}");
    }
    let e = err(hyst(&[
        "fit", &late_path, "--lag", "force=1", "--lag", "force=2",
    ]));
    assert!(e.contains("--lag"), "{e}");
}

/// `--negate` flips a channel's sign as the record is read; a record that gives out energy (its
/// force flipped) is named in a note by the fitting verbs, and fitted with `--negate force` it is
/// the record as measured, to the last bit.
#[test]
fn negate_flips_a_channel_and_a_record_that_gives_out_energy_is_named() {
    let history = write("negated.csv", "displacement (mm)\n0.5\n1.0\n");
    let params = write("bw.json", BW);
    let out = ok(hyst(&[
        "simulate",
        &history,
        "--params",
        &params,
        "--negate",
        "displacement",
    ]));
    let text = String::from_utf8(out.stdout.clone()).unwrap();
    assert!(text.lines().nth(1).unwrap().starts_with("-0.5,"), "{text}");
    assert!(cli::stderr(&out).contains("the sign of every sample flipped"));
    let e = err(hyst(&[
        "simulate", &history, "--params", &params, "--negate", "force",
    ]));
    assert!(e.contains("cannot negate the force"), "{e}");
    let e = err(hyst(&[
        "simulate",
        &history,
        "--params",
        &params,
        "--negate",
        "displacement",
        "--negate",
        "displacement",
    ]));
    assert!(e.contains("negated once"), "{e}");

    let clean = column_record();
    let flipped = column_record_with_force(|f| format!("{}", -f));
    let (clean_nrmse, note) = lsq_fit(&write("clean.csv", &clean), &[]);
    assert!(!note.contains("gives out energy"), "{note}");
    let path = write("flipped.csv", &flipped);
    let (bad, note) = lsq_fit(&path, &[]);
    assert!(
        note.contains("gives out energy") && note.contains("--negate force"),
        "{note}"
    );
    assert!(bad > 0.5, "{bad}");
    let (fixed, note) = lsq_fit(&path, &["--negate", "force"]);
    assert!(!note.contains("gives out energy"), "{note}");
    assert_eq!(fixed, clean_nrmse);
}

/// `--max-rows` reads the head of a file whose tail is something else (here a logger's
/// summary lines), says how much it left, and fits what it read as if the tail were not there.
#[test]
fn max_rows_reads_the_head_of_a_file_and_says_what_it_left() {
    let clean = column_record();
    let rows = clean.lines().count() - 1;
    let tailed = write(
        "tailed.csv",
        &format!("{clean}test ended\npeak force,12.3\n"),
    );
    let e = err(hyst(&["fit", &tailed, "--method", "lsq"]));
    assert!(e.contains("tailed.csv:"), "{e}");
    let rows_arg = rows.to_string();
    let (nrmse, note) = lsq_fit(&tailed, &["--max-rows", &rows_arg]);
    assert!(
        note.contains(&format!(
            "2 rows from line {} on not read, as asked",
            rows + 2
        )),
        "{note}"
    );
    assert_eq!(nrmse, lsq_fit(&write("head.csv", &clean), &[]).0);
    let e = err(hyst(&["fit", &tailed, "--max-rows", "0"]));
    assert!(e.contains("--max-rows") && e.contains("0"), "{e}");
}

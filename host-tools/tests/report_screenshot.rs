//! The sample report, with every plot kind, rendered by headless Chromium:
//! the screenshot must have the window's size, show the whole page, carry
//! ink, and show each colour the plots use.
//!
//! Needs Debian's `chromium` (`apt-get install -y chromium`); without it the
//! test says so and passes without checking. `HYST_CHROMIUM` names another
//! browser binary.

// Each test crate uses part of the shared gallery.
#[allow(dead_code)]
#[path = "support/gallery.rs"]
mod gallery;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use hyst::report::style::{self, Colour};

/// Window size of the screenshot: wider than the page's 1000 px column, and
/// taller than the whole page, so that one shot holds all of it.
const WIDTH: u32 = 1100;
const HEIGHT: u32 = 6000;

fn chromium() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("HYST_CHROMIUM") {
        return Some(PathBuf::from(p));
    }
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .flat_map(|dir| ["chromium", "chromium-browser"].map(|b| dir.join(b)))
        .find(|p| p.is_file())
}

/// Runs the browser to screenshot `page` into `png`, failing after 2 minutes.
fn screenshot(browser: &Path, page: &Path, png: &Path, profile: &Path) {
    let mut child = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
            "--force-device-scale-factor=1",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("--window-size={WIDTH},{HEIGHT}"))
        .arg(format!("--screenshot={}", png.display()))
        .arg(format!("file://{}", page.display()))
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("start the browser");
    let deadline = Instant::now() + Duration::from_secs(120);
    loop {
        if let Some(status) = child.try_wait().expect("wait for the browser") {
            assert!(status.success(), "browser failed: {status}");
            return;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("browser did not finish within 2 minutes");
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// An RGB image.
struct Image {
    width: u32,
    height: u32,
    rgb: Vec<[u8; 3]>,
}

fn decode(png_path: &Path) -> Image {
    let file = std::io::BufReader::new(std::fs::File::open(png_path).expect("screenshot written"));
    let mut decoder = png::Decoder::new(file);
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info().expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size().expect("buffer size")];
    let info = reader.next_frame(&mut buf).expect("a frame");
    let channels = match info.color_type {
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        other => panic!("unexpected PNG colour type {other:?}"),
    };
    let rgb = buf[..info.buffer_size()]
        .chunks_exact(channels)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    Image {
        width: info.width,
        height: info.height,
        rgb,
    }
}

fn near(p: [u8; 3], c: Colour, tolerance: u8) -> bool {
    p[0].abs_diff(c.0) <= tolerance
        && p[1].abs_diff(c.1) <= tolerance
        && p[2].abs_diff(c.2) <= tolerance
}

#[test]
fn sample_report_renders_in_headless_chromium() {
    let Some(browser) = chromium() else {
        eprintln!(
            "SKIPPED sample_report_renders_in_headless_chromium: no chromium on PATH \
             (install it with `apt-get install -y chromium`, or set HYST_CHROMIUM)"
        );
        return;
    };
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("report-screenshot");
    let profile = dir.join("profile");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&profile).unwrap();
    let page = dir.join("gallery.html");
    let png_path = dir.join("gallery.png");
    gallery::report().write(&page).unwrap();
    screenshot(&browser, &page, &png_path, &profile);
    eprintln!("screenshot: {}", png_path.display());

    let img = decode(&png_path);
    assert_eq!((img.width, img.height), (WIDTH, HEIGHT));

    // One pass over the pixels: ink per row, and pixels of each plot colour.
    let expected = [
        ("measured grey", style::MEASURED),
        ("blue", style::BLUE),
        ("vermillion", style::VERMILLION),
        ("green", style::GREEN),
        ("purple", style::PURPLE),
        ("orange", style::ORANGE),
        ("cycle band grey", style::BAND),
    ];
    let white = Colour(255, 255, 255);
    let mut counts = [0usize; 7];
    let (mut inked, mut last_inked_row) = (0usize, 0usize);
    for (r, row) in img.rgb.chunks_exact(img.width as usize).enumerate() {
        for &p in row {
            if near(p, white, 8) {
                continue;
            }
            inked += 1;
            last_inked_row = r;
            if let Some(k) = expected.iter().position(|(_, c)| near(p, *c, 6)) {
                counts[k] += 1;
            }
        }
    }

    // Ink: the page is not blank.
    let share = inked as f64 / img.rgb.len() as f64;
    eprintln!("non-white pixels: {inked} ({:.1}%)", 100.0 * share);
    assert!(share > 0.03, "page looks blank: {:.2}% ink", 100.0 * share);

    // The whole page fits: the last 100 rows are empty.
    eprintln!("page ends at row {last_inked_row} of {HEIGHT}");
    assert!(
        last_inked_row < HEIGHT as usize - 100,
        "the page runs past the window; raise HEIGHT"
    );

    // Every colour the plots use shows up, in quantity.
    for ((name, colour), count) in expected.iter().zip(counts) {
        eprintln!("{name} {colour}: {count} pixels");
        assert!(
            count >= 500,
            "{name} ({colour}) barely present: {count} pixels"
        );
    }
}

/// The page `hyst discover --report` writes, for the record with hidden
/// pinching: it must render whole, with the measured loops (grey), the
/// first and final models side by side (blue, vermillion) and the branch
/// colours of the residual map.
#[test]
fn discovery_report_renders_in_headless_chromium() {
    let Some(browser) = chromium() else {
        eprintln!("SKIPPED discovery_report_renders_in_headless_chromium: no chromium on PATH");
        return;
    };
    use hyst::discover::{discover, page, WeighOptions};
    use hyst::fit::problem::Problem;
    use hyst::fit::run::{self, Method, Quiet};
    let path = format!(
        "{}/../../shared/data/synthetic/s1_hidden_pinching.csv",
        env!("CARGO_MANIFEST_DIR")
    );
    let record = hyst::data::read(&path, &Default::default()).unwrap();
    let exp = hyst::fit::experiment::Experiment::from_record(&record, None).unwrap();
    let problem = Problem::new(hyst::model::ModelSpec::BW, exp, &[]).unwrap();
    let outcome = run::fit(&problem, Method::Auto, &problem.par.default_start(), &Quiet).unwrap();
    let found = discover(problem, outcome, &WeighOptions::default(), |_| {}).unwrap();
    assert_eq!(found.rungs.len(), 2, "bw, then bw+pinching");
    let units = page::Units {
        displacement: "mm",
        force: "kN",
    };
    let report = page::discovery_page("Discovery on s1", &found, &units).unwrap();

    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("discovery-screenshot");
    let profile = dir.join("profile");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&profile).unwrap();
    let html = dir.join("discovery.html");
    let png_path = dir.join("discovery.png");
    report.write(&html).unwrap();
    let text = std::fs::read_to_string(&html).unwrap();
    assert!(
        !text.contains("http://") && !text.contains("https://") && !text.contains("<script"),
        "self-contained"
    );
    for figure in [
        "ladder",
        "Before and after",
        "Hysteresis loops",
        "Residual",
        "per cycle",
    ] {
        assert!(
            text.to_lowercase().contains(&figure.to_lowercase()),
            "missing {figure}"
        );
    }
    screenshot(&browser, &html, &png_path, &profile);
    eprintln!("screenshot: {}", png_path.display());
    let img = decode(&png_path);
    assert_eq!((img.width, img.height), (WIDTH, HEIGHT));
    let white = Colour(255, 255, 255);
    let colours = [
        ("measured grey", style::MEASURED),
        ("blue", style::BLUE),
        ("vermillion", style::VERMILLION),
    ];
    let mut counts = [0usize; 3];
    let mut inked = 0usize;
    for &p in &img.rgb {
        if near(p, white, 8) {
            continue;
        }
        inked += 1;
        if let Some(k) = colours.iter().position(|(_, c)| near(p, *c, 6)) {
            counts[k] += 1;
        }
    }
    let share = inked as f64 / img.rgb.len() as f64;
    assert!(share > 0.03, "page looks blank: {:.2}% ink", 100.0 * share);
    for ((name, colour), count) in colours.iter().zip(counts) {
        eprintln!("{name} {colour}: {count} pixels");
        assert!(
            count >= 500,
            "{name} ({colour}) barely present: {count} pixels"
        );
    }
}

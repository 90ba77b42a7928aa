//! The CSV report and the plots as files: the report has exactly the documented columns and
//! reads back; plots are valid PNG/SVG; bad inputs give errors naming the file, not panics.

use iris::image::metrics::ErrorMetrics;
use iris::measure::plot::{plot_error_vs_time, Series, PLOT_SIZE};
use iris::measure::report::{write_csv, ReportRow, CSV_HEADER};
use std::path::PathBuf;

/// Removes a scratch directory unless `IRIS_KEEP_TEST_OUTPUT` is set (to look at the plots).
fn cleanup(dir: &std::path::Path) {
    if std::env::var_os("IRIS_KEEP_TEST_OUTPUT").is_none() {
        let _ = std::fs::remove_dir_all(dir);
    }
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("iris-report-plot-{}-{name}", std::process::id()));
    cleanup(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

fn row(run: &str, stage: &str, t: f64, spp: u64, err: Option<ErrorMetrics>) -> ReportRow {
    ReportRow {
        run: run.into(),
        stage: stage.into(),
        wall_s: t,
        samples: spp,
        passes: 3,
        rays: 123_456_789_012,
        photons: 42,
        error: err,
        estimate: err.map(|m| ErrorMetrics {
            rmse: m.rmse * 1.1,
            ..m
        }),
        denoised: err.map(|m| ErrorMetrics {
            rmse: m.rmse * 0.5,
            ..m
        }),
        denoise_s: err.map(|_| 0.125),
        display_estimate: err.map(|m| m.mae * 0.25),
        display_error: err.map(|m| m.mae * 0.5),
    }
}

#[test]
fn csv_has_documented_columns_and_reads_back() {
    let dir = scratch("csv");
    let path = dir.join("report.csv");
    let m = ErrorMetrics {
        rmse: 0.123_456_789_012_345_67,
        rel_mse: 1e-7,
        mae: 3.0,
    };
    let rows = vec![
        row("path", "load", 0.01, 0, None),
        row("path", "build", 0.25, 0, None),
        row("path", "render", 1.0 / 3.0, 4, Some(m)),
    ];
    write_csv(&path, &rows).expect("write csv");
    let text = std::fs::read_to_string(&path).expect("read csv");
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], CSV_HEADER);
    assert_eq!(
        CSV_HEADER,
        "run,stage,wall_s,samples_per_pixel,passes,rays,photons,rmse,rel_mse,mae,est_rmse,est_rel_mse,est_mae,denoised_rmse,denoised_rel_mse,denoised_mae,denoise_s,display_est,display_rmse"
    );
    assert_eq!(lines.len(), 1 + rows.len(), "one line per row:\n{text}");
    for (line, r) in lines[1..].iter().zip(&rows) {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells.len(), 19, "{line}");
        assert_eq!((cells[0], cells[1]), (r.run.as_str(), r.stage.as_str()));
        // Shortest round-trip formatting: the exact values come back.
        assert_eq!(cells[2].parse::<f64>().unwrap(), r.wall_s);
        assert_eq!(cells[3].parse::<u64>().unwrap(), r.samples);
        assert_eq!(cells[4].parse::<u32>().unwrap(), r.passes);
        assert_eq!(cells[5].parse::<u64>().unwrap(), r.rays);
        assert_eq!(cells[6].parse::<u64>().unwrap(), r.photons);
        let metrics = |c: &[&str]| -> Option<ErrorMetrics> {
            if c.iter().all(|s| s.is_empty()) {
                return None;
            }
            Some(ErrorMetrics {
                rmse: c[0].parse().unwrap(),
                rel_mse: c[1].parse().unwrap(),
                mae: c[2].parse().unwrap(),
            })
        };
        assert_eq!(metrics(&cells[7..10]), r.error);
        assert_eq!(metrics(&cells[10..13]), r.estimate);
        assert_eq!(metrics(&cells[13..16]), r.denoised);
        assert_eq!(cells[16].parse::<f64>().ok(), r.denoise_s, "{line}");
        assert_eq!(cells[17].parse::<f64>().ok(), r.display_estimate, "{line}");
        assert_eq!(cells[18].parse::<f64>().ok(), r.display_error, "{line}");
    }
    // Rewriting replaces the file (atomic write, no leftovers).
    write_csv(&path, &rows[..1]).expect("rewrite");
    assert_eq!(std::fs::read_to_string(&path).unwrap().lines().count(), 2);
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
    cleanup(&dir);
}

#[test]
fn csv_to_missing_directory_is_an_error() {
    let dir = scratch("csv-missing");
    let path = dir.join("no/such/dir/report.csv");
    let err = write_csv(&path, &[]).expect_err("missing directory");
    assert!(err.to_string().contains("report.csv"), "{err}");
    cleanup(&dir);
}

fn two_series() -> Vec<Series> {
    let curve = |c: f64, k: f64| -> Vec<(f64, f64)> {
        (0..6)
            .map(|i| {
                let t = 0.05 * 2f64.powi(i);
                (t, c * t.powf(k))
            })
            .collect()
    };
    vec![
        Series {
            label: "path tracer".into(),
            points: curve(0.2, -0.5),
        },
        Series {
            label: "sppm".into(),
            points: curve(0.1, -0.33),
        },
    ]
}

#[test]
fn png_plot_is_a_valid_png_of_the_documented_size() {
    let dir = scratch("png");
    let path = dir.join("err.PNG");
    plot_error_vs_time(&path, "Error against time", "RMSE", &two_series()).expect("plot");
    let img = image::open(&path).expect("decodes as an image").to_rgb8();
    assert_eq!(img.dimensions(), PLOT_SIZE);
    // Something besides the white background was drawn (lines, text): count dark pixels.
    let dark = img
        .pixels()
        .filter(|p| p.0.iter().all(|&c| c < 128))
        .count();
    assert!(dark > 1000, "only {dark} dark pixels");
    cleanup(&dir);
}

#[test]
fn svg_plot_is_valid_and_names_the_series() {
    let dir = scratch("svg");
    let path = dir.join("err.svg");
    plot_error_vs_time(&path, "Error against time", "relative MSE", &two_series()).expect("plot");
    let svg = std::fs::read_to_string(&path).expect("utf-8 svg");
    let start = svg.trim_start();
    assert!(
        start.starts_with("<svg") || start.starts_with("<?xml"),
        "{}",
        &svg[..80]
    );
    assert!(svg.trim_end().ends_with("</svg>"));
    assert!(
        svg.contains("path tracer (slope −0.50)"),
        "legend with slope"
    );
    assert!(svg.contains("sppm (slope −0.33)"));
    assert!(svg.contains("relative MSE"));
    cleanup(&dir);
}

#[test]
fn bad_extension_names_the_file() {
    let dir = scratch("ext");
    for name in ["err.jpg", "err", "err.png.txt"] {
        let path = dir.join(name);
        let err = plot_error_vs_time(&path, "t", "y", &two_series()).expect_err(name);
        assert!(err.to_string().contains(name), "{err}");
        assert!(!path.exists());
    }
    cleanup(&dir);
}

#[test]
fn empty_and_non_positive_series_do_not_panic() {
    let dir = scratch("degenerate");
    let cases: Vec<Vec<Series>> = vec![
        vec![],
        vec![Series {
            label: "empty".into(),
            points: vec![],
        }],
        vec![Series {
            label: "zeros".into(),
            points: vec![(0.0, 1.0), (1.0, 0.0), (-2.0, -1.0), (f64::NAN, 1.0)],
        }],
        vec![Series {
            label: "one point".into(),
            points: vec![(1.0, 0.5), (2.0, 0.0)],
        }],
    ];
    for (i, series) in cases.iter().enumerate() {
        for ext in ["png", "svg"] {
            let path = dir.join(format!("case{i}.{ext}"));
            plot_error_vs_time(&path, "degenerate", "RMSE", series).expect("no error");
            assert!(std::fs::metadata(&path).unwrap().len() > 0);
        }
    }
    let svg = std::fs::read_to_string(dir.join("case3.svg")).unwrap();
    assert!(svg.contains("one point (slope n/a)"));
    cleanup(&dir);
}

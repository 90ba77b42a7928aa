//! The error levels of `iris converge`: for each of [`LEVELS`] (relative RMSE, coarse to
//! fine), which run reached it first and when. Curves are (wall seconds, relative RMSE)
//! points as [`super::recorder::points`] makes them; times have checkpoint resolution.

/// Error levels (relative RMSE) reported by `iris converge`, coarse to fine.
pub const LEVELS: [f64; 5] = [0.5, 0.2, 0.1, 0.05, 0.02];

/// The first time each run's error (relative RMSE, reference if present else estimate)
/// reached `level`: one entry per run, `None` if it never did.
pub fn first_reached(runs: &[(String, Vec<(f64, f64)>)], level: f64) -> Vec<Option<f64>> {
    runs.iter()
        .map(|(_, pts)| pts.iter().find(|(_, e)| *e <= level).map(|(t, _)| *t))
        .collect()
}

/// The levels table of `iris converge`: for each of [`LEVELS`], the run that reached it
/// first and when (checkpoint resolution: checkpoints fall at 1, 2, 4, … samples or passes).
pub fn levels_table(runs: &[(String, Vec<(f64, f64)>)]) -> String {
    let mut s = String::from("relative error  first to reach it\n");
    for level in LEVELS {
        let times = first_reached(runs, level);
        let best = times
            .iter()
            .enumerate()
            .filter_map(|(i, t)| t.map(|t| (i, t)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        let others: Vec<String> = runs
            .iter()
            .zip(&times)
            .map(|((name, _), t)| match t {
                Some(t) => format!("{name} {t:.2} s"),
                None => format!("{name} not reached"),
            })
            .collect();
        let first = match best {
            Some((i, t)) => format!("{} at {t:.2} s", runs[i].0),
            None => "none".into(),
        };
        s.push_str(&format!(
            "{level:<14}  {first:<20}  ({})\n",
            others.join(", ")
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_pick_the_earliest_run() {
        // Hand-made curves: "a" is faster to 0.5 and 0.2, "b" alone reaches 0.05.
        let runs = vec![
            ("a".to_string(), vec![(0.1, 0.6), (0.2, 0.3), (0.4, 0.15)]),
            ("b".to_string(), vec![(0.3, 0.45), (0.6, 0.04)]),
        ];
        assert_eq!(first_reached(&runs, 0.5), vec![Some(0.2), Some(0.3)]);
        assert_eq!(first_reached(&runs, 0.05), vec![None, Some(0.6)]);
        let t = levels_table(&runs);
        let line = |l: &str| t.lines().find(|x| x.starts_with(l)).unwrap().to_string();
        assert!(line("0.5 ").contains("a at 0.20 s"), "{t}");
        assert!(line("0.1 ").contains("b at 0.60 s"), "{t}");
        assert!(line("0.02").contains("none"), "{t}");
    }
}

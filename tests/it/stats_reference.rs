//! `covga::stats` against reference values computed by scipy
//! (`tests/fixtures/stats-reference.json`, written by `python/tests/make_stats_fixtures.py`):
//! the rank-sum test exact without ties (`mannwhitneyu(method="exact")`), exact with ties
//! (scipy's exact permutation test of the rank sum) and normal beyond 50 values; the
//! signed-rank test likewise (`wilcoxon`, its exact permutation test, `method="approx"`);
//! Kruskal–Wallis (`kruskal`) and the sign test (`binomtest`).

use covga::stats::{Method, kruskal_wallis, mann_whitney, sign_test, wilcoxon_signed_rank};
use serde_json::Value;

fn fixture() -> Value {
    let text = std::fs::read_to_string("tests/fixtures/stats-reference.json").expect("fixture");
    serde_json::from_str(&text).expect("JSON")
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect()
}

fn close(got: f64, want: f64, what: &str) {
    assert!((got - want).abs() <= 1e-9 * want.abs().max(1e-3), "{what}: covga {got}, scipy {want}");
}

#[test]
fn the_rank_sum_test_agrees_with_scipy() {
    let f = fixture();
    for (k, case) in f["mann_whitney"].as_array().unwrap().iter().enumerate() {
        let (a, b) = (numbers(&case["a"]), numbers(&case["b"]));
        let t = mann_whitney(&a, &b).expect("a test");
        let method = if a.len() + b.len() > 50 { Method::Normal } else { Method::Exact };
        assert_eq!(t.method, method, "case {k}");
        close(t.u, case["u"].as_f64().unwrap(), &format!("U of case {k}"));
        close(t.p_value, case["p"].as_f64().unwrap(), &format!("p of case {k}"));
    }
}

#[test]
fn the_signed_rank_test_agrees_with_scipy() {
    let f = fixture();
    for (k, case) in f["wilcoxon"].as_array().unwrap().iter().enumerate() {
        let (a, b) = (numbers(&case["a"]), numbers(&case["b"]));
        let t = wilcoxon_signed_rank(&a, &b).expect("a test");
        assert_eq!(t.pairs as u64, case["pairs"].as_u64().unwrap(), "case {k}");
        let method = if t.pairs > 50 { Method::Normal } else { Method::Exact };
        assert_eq!(t.method, method, "case {k}");
        close(t.w_plus, case["w_plus"].as_f64().unwrap(), &format!("W+ of case {k}"));
        close(t.p_value, case["p"].as_f64().unwrap(), &format!("p of case {k}"));
    }
}

#[test]
fn kruskal_wallis_and_the_sign_test_agree_with_scipy() {
    let f = fixture();
    for (k, case) in f["kruskal"].as_array().unwrap().iter().enumerate() {
        let groups: Vec<Vec<f64>> = case["groups"].as_array().unwrap().iter().map(numbers).collect();
        let t = kruskal_wallis(&groups).expect("a test");
        close(t.h, case["h"].as_f64().unwrap(), &format!("H of case {k}"));
        close(t.p_value, case["p"].as_f64().unwrap(), &format!("p of case {k}"));
    }
    for case in f["sign"].as_array().unwrap() {
        let (above, below) = (case["above"].as_u64().unwrap() as usize, case["below"].as_u64().unwrap() as usize);
        let values: Vec<f64> = std::iter::repeat_n(1.0, above).chain(std::iter::repeat_n(-1.0, below)).collect();
        close(sign_test(&values, 0.0).unwrap(), case["p"].as_f64().unwrap(), &format!("{above} of {}", above + below));
    }
}

//! Simplification preserves values; identities come out as the expected nodes.

use super::*;

#[test]
fn simplification_preserves_value() {
    let mut rng = Rng::new(6);
    let (mut compared, mut tight) = (0, 0);
    for _ in 0..3000 {
        let mut g = Graph::new();
        let ast = Ast::random(&mut rng, 5, &GENERAL_CONSTS);
        let id = ast.build(&mut g);
        for _ in 0..3 {
            let x: Vec<f64> = (0..VARS.len()).map(|_| rng.range(-2.0, 2.0)).collect();
            let (reference, e_ref) = ast.eval(&x);
            if !reference.is_finite() || !e_ref.is_finite() || reference.abs() > 1e100 {
                continue; // outside the expression's domain (√ of a negative, overflow, 0⁻¹)
            }
            let (en, list) = bindings(&mut g, &x);
            let value = g.eval(id, &en);
            let (_, e_graph) = graph_error_bound(&g, id, &list, &mut HashMap::new());
            if !e_graph.is_finite() {
                continue;
            }
            compared += 1;
            if e_ref + e_graph <= 1e-10 * reference.abs().max(1e-300) {
                tight += 1;
            }
            assert!(
                (value - reference).abs() <= 16.0 * (e_ref + e_graph) + f64::MIN_POSITIVE,
                "{ast:?} at {x:?}: graph {value}, reference {reference} (bounds {e_ref:e}, {e_graph:e})"
            );
        }
    }
    // Most comparisons must be tight ones (the bound is not allowed to hide everything).
    assert!(
        compared > 3000 && tight * 10 > compared * 6,
        "compared {compared}, tight {tight}"
    );
}

/// Constants for the structural identities: small dyadic rationals, for which 2c + 3c = 5c and
/// c·c⁻¹ = 1 hold exactly in f64 (checked below), so the identities can be demanded as equal
/// nodes.
const DYADIC_CONSTS: [f64; 8] = [0.5, 0.75, 1.5, 2.0, 3.0, -0.25, -1.25, 4.0];

#[test]
fn simplification_identities_are_structural() {
    for c in DYADIC_CONSTS {
        assert_eq!(2.0 * c + 3.0 * c, 5.0 * c);
        assert_eq!(c * c.powi(-1), 1.0);
    }
    let mut rng = Rng::new(7);
    let (mut nontrivial, mut collected, mut reciprocal) = (0, 0, 0);
    for _ in 0..2000 {
        let mut g = Graph::new();
        let a = Ast::random(&mut rng, 4, &DYADIC_CONSTS).build(&mut g);
        // A constant, or an expression dividing by a folded 0 (infinite everywhere), has no
        // identities to keep.
        // Non-canonical nodes (a product nested in a product, a base repeated in a product) come
        // from the engine bug shown by `bug_product_not_flat_after_power_folding`; identities
        // cannot hold structurally for them.
        if g.as_const(a).is_some()
            || !is_canonical(&g, a)
            || contains(
                &g,
                a,
                &|n| matches!(n, Node::Pow(b, _) if matches!(g.node(*b), Node::Const(0))),
            )
        {
            continue;
        }
        nontrivial += 1;
        // a − a = 0
        let d = g.sub(a, a);
        assert!(
            g.is_const(d, 0.0),
            "a − a = {} for a = {}",
            show(&g, d),
            show(&g, a)
        );
        // a · a⁻¹ = 1, except for a = c·Sⁿ (constant times a power of a sum): a⁻¹ = c⁻¹·S⁻ⁿ
        // is distributed when n = −1, giving a different sum node (see the ignored test
        // `bug_reciprocal_of_scaled_reciprocal_sum_does_not_cancel`).
        // The folded coefficient c·c⁻¹ must also be exactly 1 in f64 (not so for c = 3⁹, 49/16,
        // √3.75, …): rounding, not simplification.
        let scaled_single = matches!(g.node(a), Node::Mul(fs)
            if fs.len() == 2 && fs.iter().any(|&f| g.as_const(f).is_some()));
        let coefficient = match g.node(a) {
            Node::Mul(fs) => fs.iter().find_map(|&f| g.as_const(f)).unwrap_or(1.0),
            _ => 1.0,
        };
        if !scaled_single && coefficient * coefficient.powi(-1) == 1.0 {
            reciprocal += 1;
            let inv = g.powi(a, -1);
            let one = g.mul(a, inv);
            assert!(
                g.is_const(one, 1.0),
                "a·a⁻¹ ≠ 1: {} for a = {}",
                show(&g, one),
                show(&g, a)
            );
            let q = g.div(a, a);
            assert!(g.is_const(q, 1.0), "a/a ≠ 1 for a = {}", show(&g, a));
        }
        // sqrt(a)² = a (and sqrt(a)⁴ = a²)
        let s = g.sqrt(a);
        let s2 = g.powi(s, 2);
        assert_eq!(s2, a, "sqrt(a)² ≠ a");
        let s4 = g.powi(s, 4);
        let a2 = g.powi(a, 2);
        assert_eq!(s4, a2, "sqrt(a)⁴ ≠ a²");
        // 2a + 3a = 5a
        let a_2 = g.scale(2.0, a);
        let a_3 = g.scale(3.0, a);
        let lhs = g.add(a_2, a_3);
        let rhs = g.scale(5.0, a);
        // Coefficients are folded in f64: demand equal nodes when 2c + 3c = 5c is exact for
        // every constant c in a (folded reciprocals such as 1/1.25 are not dyadic).
        let exact = !contains(
            &g,
            a,
            &|n| matches!(n, Node::Const(b) if { let c = f64::from_bits(*b); 2.0 * c + 3.0 * c != 5.0 * c }),
        );
        if exact {
            collected += 1;
            assert_eq!(
                lhs,
                rhs,
                "2a + 3a ≠ 5a: {} vs {} for a = {}",
                show(&g, lhs),
                show(&g, rhs),
                show(&g, a)
            );
        }
        // a + a = 2a, a·a = a²
        let aa = g.add(a, a);
        assert_eq!(aa, a_2, "a + a ≠ 2a");
        let sq = g.mul(a, a);
        // Structurally only without square roots: sqrt(p)^(2k) of a product p re-enters a
        // product unflattened (see the ignored test `bug_product_not_flat_after_power_folding`).
        if !contains(
            &g,
            a,
            &|n| matches!(n, Node::Call(f, _) if f.name() == "sqrt"),
        ) {
            assert_eq!(
                sq,
                a2,
                "a·a ≠ a²: {} vs {} for a = {}",
                show(&g, sq),
                show(&g, a2),
                show(&g, a)
            );
        }
        let x: Vec<f64> = (0..VARS.len()).map(|_| rng.range(0.5, 2.0)).collect();
        let (en, _) = bindings(&mut g, &x);
        let (vs, va) = (g.eval(sq, &en), g.eval(a2, &en));
        if vs.is_finite() {
            assert!((vs - va).abs() <= 1e-12 * vs.abs(), "a·a = {vs}, a² = {va}");
        }
        // Commutativity through interning.
        let b = g.input("x1");
        let ab = g.mul(a, b);
        let ba = g.mul(b, a);
        assert_eq!(ab, ba);
        let apb = g.add(a, b);
        let bpa = g.add(b, a);
        assert_eq!(apb, bpa);
    }
    assert!(
        nontrivial > 1000 && collected > 800 && reciprocal > 800,
        "{nontrivial} non-constant expressions, {collected} with exact coefficients, {reciprocal} reciprocal checks"
    );
}

/// Bug reproducer (engine): `product` powers each collected factor with `powi`, but does not
/// flatten or re-collect the result. When the power folds into a product — sqrt(p)^(2k) → p^k
/// for a product p, or (c·x)^n → cⁿ·xⁿ — the outer product keeps a nested `Mul` (with a second
/// constant), and like factors are not combined: a·a ≠ a² as nodes, x·x⁻¹ survives.
/// Values are preserved; canonical form (and thus sharing and cancellation) is not.
#[test]
fn product_stays_flat_after_power_folding() {
    let mut g = Graph::new();
    let mut failures = Vec::new();
    let (x0, x1, x2) = (g.input("x0"), g.input("x1"), g.input("x2"));
    // sqrt(x1)·sqrt(x2·x0), squared: x1·(x0·x2) instead of x0·x1·x2.
    let p = g.mul(x2, x0);
    let s = g.sqrt(p);
    let s1 = g.sqrt(x1);
    let a = g.product(&[s1, s]);
    let sq = g.mul(a, a);
    let a2 = g.powi(a, 2);
    if sq != a2 {
        failures.push(format!("a·a = {} but a² = {}", show(&g, sq), show(&g, a2)));
    }
    // sqrt(x0·x1)·sqrt(x0·x1)·x0⁻¹ must cancel to x1.
    let q = g.mul(x0, x1);
    let sq = g.sqrt(q);
    let inv = g.powi(x0, -1);
    let direct = g.product(&[sq, sq, inv]);
    if direct != x1 {
        failures.push(format!(
            "sqrt(x0·x1)·sqrt(x0·x1)·x0⁻¹ = {}",
            show(&g, direct)
        ));
    }
    // sqrt(3·x0)·sqrt(3·x0)·x0 builds x0·(x0·3), not 3·x0²; doubling it gives x0·(x0·3)·2
    // (two constants in one product). Such nodes also break `substitute` idempotence and
    // a − a = 0 further up (found by the random tests with other seeds).
    let three = g.constant(3.0);
    let t = g.mul(three, x0);
    let s3 = g.sqrt(t);
    let a = g.product(&[s3, s3, x0]);
    let x0sq = g.powi(x0, 2);
    let want = g.scale(3.0, x0sq);
    if a != want {
        let twice = g.add(a, a);
        failures.push(format!(
            "sqrt(3x0)·sqrt(3x0)·x0 = {} (want {}); doubled: {}",
            show(&g, a),
            show(&g, want),
            show(&g, twice)
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Bug reproducer (engine): a constant times a single sum is distributed (`c·S → Σ c·tᵢ`), so
/// for a = 4/S the reciprocal a⁻¹ = S/4 becomes the *different* sum node Σ tᵢ/4 and a·a⁻¹ does
/// not cancel to 1 (the value is 1; the node is 4·S⁻¹·(S/4)). Found by
/// `simplification_identities_are_structural` with a = 4·(sin(x0) − 0.75·x0 − x1)⁻¹.
#[test]
fn reciprocal_of_scaled_reciprocal_sum_cancels() {
    let mut g = Graph::new();
    let (x0, x1) = (g.input("x0"), g.input("x1"));
    let sx = g.sin(x0);
    let t = g.scale(-0.75, x0);
    let nx1 = g.neg(x1);
    let sum = g.sum(&[sx, t, nx1]);
    let inv = g.powi(sum, -1);
    let a = g.scale(4.0, inv);
    let q = g.div(a, a);
    assert!(g.is_const(q, 1.0), "a/a = {}", show(&g, q));
}

/// Re-simplification through `substitute` is idempotent: rebuilding an expression with the
/// identity map, or with identity-ish maps xᵢ → (xᵢ + w) − w and xᵢ → xᵢ·w·w⁻¹, returns the very
/// same node; and a genuine substitution has the value of the original at the substituted point.
#[test]
fn substitution_resimplifies_to_the_same_node_and_value() {
    let mut rng = Rng::new(8);
    let (mut checked_values, mut tight, mut structural) = (0, 0, 0);
    for _ in 0..1500 {
        let mut g = Graph::new();
        let ast = Ast::random(&mut rng, 5, &GENERAL_CONSTS);
        let id = ast.build(&mut g);
        let w = g.input("w");
        let syms: Vec<Symbol> = VARS.iter().map(|n| g.symbol(n)).collect();
        // Idempotence holds for canonical nodes; the non-canonical ones produced by the engine
        // bug of `bug_product_not_flat_after_power_folding` re-simplify to their canonical form.
        if is_canonical(&g, id) {
            structural += 1;
            let identity: HashMap<Symbol, ExprId> =
                syms.iter().map(|&s| (s, g.input_of(s))).collect();
            assert_eq!(
                g.substitute(id, &identity),
                id,
                "identity substitution changed {ast:?}"
            );
            let shifted: HashMap<Symbol, ExprId> = syms
                .iter()
                .map(|&s| {
                    let x = g.input_of(s);
                    let t = g.add(x, w);
                    (s, g.sub(t, w))
                })
                .collect();
            assert_eq!(
                g.substitute(id, &shifted),
                id,
                "x → (x + w) − w changed {ast:?}"
            );
            let scaled: HashMap<Symbol, ExprId> = syms
                .iter()
                .map(|&s| {
                    let x = g.input_of(s);
                    let t = g.mul(x, w);
                    (s, g.div(t, w))
                })
                .collect();
            assert_eq!(g.substitute(id, &scaled), id, "x → x·w/w changed {ast:?}");
        }
        // x0 → x1 + x2·w (a real change): value of the result at (x, w) equals the original at
        // (x1 + x2 w, x1, x2).
        let x1 = g.input("x1");
        let x2 = g.input("x2");
        let x2w = g.mul(x2, w);
        let repl = g.add(x1, x2w);
        let sub = g.substitute(id, &HashMap::from([(syms[0], repl)]));
        let x: Vec<f64> = (0..VARS.len()).map(|_| rng.range(-2.0, 2.0)).collect();
        let wv = rng.range(-1.0, 1.0);
        let moved = [x[1] + x[2] * wv, x[1], x[2]];
        let (reference, e_ref) = ast.eval(&moved);
        if !reference.is_finite() || !e_ref.is_finite() || reference.abs() > 1e100 {
            continue;
        }
        let (mut en, mut list) = bindings(&mut g, &x);
        en.set(&mut g, "w", wv);
        list.push((g.symbol("w"), wv));
        let value = g.eval(sub, &en);
        let (_, e_graph) = graph_error_bound(&g, sub, &list, &mut HashMap::new());
        if !e_graph.is_finite() {
            continue;
        }
        // The reference rounds x1 + x2·w once more than the substituted graph does.
        let (_, e_moved) = Ast::Add(
            Box::new(Ast::Var(1)),
            Box::new(Ast::Mul(Box::new(Ast::Var(2)), Box::new(Ast::Const(wv)))),
        )
        .eval(&x);
        let e_shift = e_moved + U * moved[0].abs();
        // The graph computes the exact function of (x1, x2, w); the reference sees x0 rounded
        // by e_shift. Its sensitivity to that, by perturbing x0 and differencing:
        let e_sens = {
            let mut p = moved;
            p[0] += e_shift.max(U * moved[0].abs());
            (ast.eval(&p).0 - reference).abs()
        };
        if !e_sens.is_finite() {
            continue; // the point sits on the edge of the domain (√ of ≈ 0)
        }
        checked_values += 1;
        if e_ref + e_graph + e_sens <= 1e-10 * reference.abs() {
            tight += 1;
        }
        assert!(
            (value - reference).abs() <= 16.0 * (e_ref + e_graph + e_sens) + f64::MIN_POSITIVE,
            "substituted {ast:?} at {x:?}, w = {wv}: {value:e} vs {reference:e} (bounds {e_ref:e}, {e_graph:e}, {e_sens:e})"
        );
    }
    assert!(
        checked_values > 500 && tight * 10 > checked_values * 5 && structural > 1300,
        "{checked_values} values compared ({tight} tight), {structural} structural checks"
    );
}

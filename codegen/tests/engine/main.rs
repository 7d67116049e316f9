//! Tests of the symbolic engine itself: differentiation, simplification, the linear solver and
//! the CSE planner, each against an independent numerical computation.
//!
//! Random points and expressions come from a fixed-seed SplitMix64 generator (the codegen crate
//! has no dev-dependencies), so every run checks the same cases and a failure is reproducible
//! (set `ENGINE_TEST_SEED=n` to explore other cases).
//!
//! Tolerances, in one place:
//! - Central differences with step h = 1e-5·max(1, |x|): truncation h²|f'''|/6 ≲ 1e-10·|f'''| and
//!   rounding ≈ 2u|f|/h ≈ 2e-11·|f|, so every rule test uses 1e-6·(1 + |f'|) (the expressions
//!   are chosen on domains where f, f''' ≲ 1e2, leaving a factor ≥ 10 of margin).
//! - Value comparisons of a random expression against its simplified graph use a running rounding
//!   error bound computed alongside both evaluations (see [`Ast::eval`], [`graph_error_bound`]):
//!   the two evaluations differ only by rounding, so |graph − reference| ≤ 16·(e_ref + e_graph).
//! - Linear solves use diagonally dominant systems (condition number ≤ 9 by construction), so
//!   a backward-stable answer has relative residual ≲ n²·u·cond ≈ 1e-14; the tests use 1e-11.

// Small dense linear algebra reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use std::collections::HashMap;

use rotor_rub_codegen::derive::{
    SolveError, derivative, determinant, nth_derivative, partial, solve_linear,
};
use rotor_rub_codegen::emit::emit_formula;
use rotor_rub_codegen::expr::{Env, ExprId, Graph, Node, Symbol};
use rotor_rub_codegen::format::format_file;
use rotor_rub_codegen::ir::Group;
use rotor_rub_codegen::ir::{Formula, Output};
use rotor_rub_codegen::optimize::plan;

/// Unit roundoff of f64.
const U: f64 = f64::EPSILON / 2.0;

// ---------------------------------------------------------------------------------------------
// Deterministic random numbers.

/// SplitMix64: small, fast, good enough to sample test points.
struct Rng(u64);

impl Rng {
    /// The generator for `seed`, shifted by `ENGINE_TEST_SEED` when set (to explore other cases).
    fn new(seed: u64) -> Self {
        let shift = std::env::var("ENGINE_TEST_SEED")
            .ok()
            .and_then(|v| v.parse::<u64>().ok());
        Rng(seed.wrapping_add(shift.unwrap_or(0).wrapping_mul(0x1000_0000_0000)))
    }

    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [lo, hi).
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform integer in [0, n).
    fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}

// ---------------------------------------------------------------------------------------------
// Helpers.

fn env(g: &mut Graph, values: &[(&str, f64)]) -> Env {
    let mut e = Env::default();
    for &(n, v) in values {
        e.set(g, n, v);
    }
    e
}

/// Central difference of `id` in the symbol `name` at `values`.
fn central_difference(g: &mut Graph, id: ExprId, values: &[(&str, f64)], name: &str) -> f64 {
    let x = values
        .iter()
        .find(|(n, _)| *n == name)
        .expect("symbol bound")
        .1;
    let h = 1e-5 * x.abs().max(1.0);
    let shifted = |d: f64| -> Vec<(&str, f64)> {
        values
            .iter()
            .map(|&(n, v)| if n == name { (n, v + d) } else { (n, v) })
            .collect()
    };
    let ep = env(g, &shifted(h));
    let em = env(g, &shifted(-h));
    (g.eval(id, &ep) - g.eval(id, &em)) / (2.0 * h)
}

/// Check ∂e/∂s for every symbol in `values` against central differences (tolerance: see the
/// module docs).
fn check_partials(g: &mut Graph, e: ExprId, values: &[(&str, f64)], what: &str) {
    for &(name, _) in values {
        let s = g.symbol(name);
        let d = partial(g, e, s);
        let en = env(g, values);
        let exact = g.eval(d, &en);
        let fd = central_difference(g, e, values, name);
        assert!(
            exact.is_finite() && (exact - fd).abs() <= 1e-6 * (1.0 + exact.abs()),
            "{what}: d/d{name} at {values:?}: symbolic {exact}, central difference {fd}"
        );
    }
}

/// Whether any node of `id` satisfies `pred`.
fn contains(g: &Graph, id: ExprId, pred: &dyn Fn(&Node) -> bool) -> bool {
    pred(g.node(id)) || g.children(id).into_iter().any(|c| contains(g, c, pred))
}

/// Whether every product under `id` is flat (no product operand), collects like factors (no base
/// twice, counting `b^n` as base b) and holds at most one constant, and every sum is flat.
fn is_canonical(g: &Graph, id: ExprId) -> bool {
    let ok = match g.node(id) {
        Node::Mul(fs) => {
            let mut bases = std::collections::HashSet::new();
            let consts = fs.iter().filter(|&&f| g.as_const(f).is_some()).count();
            consts <= 1
                && fs.iter().all(|&f| match g.node(f) {
                    Node::Mul(_) => false,
                    Node::Const(_) => true,
                    Node::Pow(b, _) => bases.insert(*b),
                    _ => bases.insert(f),
                })
        }
        Node::Add(ts) => ts.iter().all(|&t| !matches!(g.node(t), Node::Add(_))),
        _ => true,
    };
    ok && g.children(id).into_iter().all(|c| is_canonical(g, c))
}

/// The expression `id` written out (for failure messages).
fn show(g: &Graph, id: ExprId) -> String {
    let list =
        |v: &[ExprId], sep: &str| v.iter().map(|&c| show(g, c)).collect::<Vec<_>>().join(sep);
    match g.node(id) {
        Node::Const(bits) => format!("{}", f64::from_bits(*bits)),
        Node::Input(s) => g.symbol_name(*s).to_owned(),
        Node::Add(ts) => format!("({})", list(ts, " + ")),
        Node::Mul(fs) => format!("({})", list(fs, "·")),
        Node::Pow(b, n) => format!("{}^{n}", show(g, *b)),
        Node::Call(f, a) => format!("{}({})", f.name(), show(g, *a)),
    }
}

// ---------------------------------------------------------------------------------------------
// Random expressions: a reference AST evaluated directly in f64, and the same AST built in the
// graph with the simplifying constructors.

#[derive(Clone, Debug)]
enum Ast {
    Var(usize),
    Const(f64),
    Add(Box<Ast>, Box<Ast>),
    Sub(Box<Ast>, Box<Ast>),
    Mul(Box<Ast>, Box<Ast>),
    Div(Box<Ast>, Box<Ast>),
    Powi(Box<Ast>, i32),
    Sqrt(Box<Ast>),
    Exp(Box<Ast>),
    Sin(Box<Ast>),
    Cos(Box<Ast>),
}

const VARS: [&str; 3] = ["x0", "x1", "x2"];

/// The one input struct of the engine tests' formulas: every symbol they use.
const TEST_GROUPS: &[Group] = &[Group {
    ty: "In",
    arg: "input",
    doc: "test inputs",
    fields: &[
        ("x0", "x0", ""),
        ("x1", "x1", ""),
        ("x2", "x2", ""),
        ("a", "a", ""),
        ("b", "b", ""),
        ("c", "c", ""),
        ("x", "x", ""),
        ("y", "y", ""),
    ],
    external: None,
}];

impl Ast {
    /// A random expression of depth ≤ `depth`. `consts` is the pool of constants.
    fn random(rng: &mut Rng, depth: usize, consts: &[f64]) -> Ast {
        if depth == 0 || rng.unit() < 0.2 {
            return if rng.unit() < 0.7 {
                Ast::Var(rng.below(VARS.len()))
            } else {
                Ast::Const(consts[rng.below(consts.len())])
            };
        }
        let sub = |rng: &mut Rng| Box::new(Ast::random(rng, depth - 1, consts));
        match rng.below(11) {
            0 | 1 => Ast::Add(sub(rng), sub(rng)),
            2 => Ast::Sub(sub(rng), sub(rng)),
            3 | 4 => Ast::Mul(sub(rng), sub(rng)),
            5 => Ast::Div(sub(rng), sub(rng)),
            6 => Ast::Powi(sub(rng), [-3, -2, -1, 2, 3, 4][rng.below(6)]),
            7 => Ast::Sqrt(sub(rng)),
            8 => Ast::Exp(sub(rng)),
            9 => Ast::Sin(sub(rng)),
            _ => Ast::Cos(sub(rng)),
        }
    }

    fn build(&self, g: &mut Graph) -> ExprId {
        match self {
            Ast::Var(i) => g.input(VARS[*i]),
            Ast::Const(c) => g.constant(*c),
            Ast::Add(a, b) => {
                let (a, b) = (a.build(g), b.build(g));
                g.add(a, b)
            }
            Ast::Sub(a, b) => {
                let (a, b) = (a.build(g), b.build(g));
                g.sub(a, b)
            }
            Ast::Mul(a, b) => {
                let (a, b) = (a.build(g), b.build(g));
                g.mul(a, b)
            }
            Ast::Div(a, b) => {
                let (a, b) = (a.build(g), b.build(g));
                g.div(a, b)
            }
            Ast::Powi(a, n) => {
                let a = a.build(g);
                g.powi(a, *n)
            }
            Ast::Sqrt(a) => {
                let a = a.build(g);
                g.sqrt(a)
            }
            Ast::Exp(a) => {
                let a = a.build(g);
                g.exp(a)
            }
            Ast::Sin(a) => {
                let a = a.build(g);
                g.sin(a)
            }
            Ast::Cos(a) => {
                let a = a.build(g);
                g.cos(a)
            }
        }
    }

    /// Value and a first-order bound of its rounding error (running error analysis: each
    /// operation adds u·|result| and propagates its operands' errors through its derivative).
    fn eval(&self, x: &[f64]) -> (f64, f64) {
        match self {
            Ast::Var(i) => (x[*i], 0.0),
            Ast::Const(c) => (*c, 0.0),
            Ast::Add(a, b) => {
                let ((a, ea), (b, eb)) = (a.eval(x), b.eval(x));
                let v = a + b;
                (v, ea + eb + U * v.abs())
            }
            Ast::Sub(a, b) => {
                let ((a, ea), (b, eb)) = (a.eval(x), b.eval(x));
                let v = a - b;
                (v, ea + eb + U * v.abs())
            }
            Ast::Mul(a, b) => {
                let ((a, ea), (b, eb)) = (a.eval(x), b.eval(x));
                let v = a * b;
                (v, a.abs() * eb + b.abs() * ea + ea * eb + U * v.abs())
            }
            Ast::Div(a, b) => {
                let ((a, ea), (b, eb)) = (a.eval(x), b.eval(x));
                let v = a / b;
                let e = if eb >= 0.5 * b.abs() {
                    f64::INFINITY
                } else {
                    (ea + v.abs() * eb) / (b.abs() - eb) + U * v.abs()
                };
                (v, e)
            }
            Ast::Powi(a, n) => {
                let (a, ea) = a.eval(x);
                let v = a.powi(*n);
                let k = f64::from(n.unsigned_abs());
                let e = if ea >= 0.25 * a.abs() / k {
                    f64::INFINITY
                } else {
                    // |d(aⁿ)| ≤ |n|·|aⁿ|/|a|·ea·(1 + O(n·ea/a)), plus ≈ 2|n| roundings.
                    2.0 * k * v.abs() / a.abs() * ea + 2.0 * k * U * v.abs()
                };
                (v, e)
            }
            Ast::Sqrt(a) => {
                let (a, ea) = a.eval(x);
                let v = a.sqrt();
                let e = (a + ea).sqrt() - (a - ea).max(0.0).sqrt() + U * v.abs();
                (v, e)
            }
            Ast::Exp(a) => {
                let (a, ea) = a.eval(x);
                let v = a.exp();
                (v, v * ea.exp_m1() + 2.0 * U * v)
            }
            Ast::Sin(a) => {
                let (a, ea) = a.eval(x);
                (a.sin(), ea + 2.0 * U)
            }
            Ast::Cos(a) => {
                let (a, ea) = a.eval(x);
                (a.cos(), ea + 2.0 * U)
            }
        }
    }
}

/// A running rounding-error bound of `Graph::eval` of `id`, computed over the graph's own nodes
/// in the order `eval` uses (sums and products left to right). Constants count as exact up to
/// 4u: folded coefficients are themselves rounded.
fn graph_error_bound(
    g: &Graph,
    id: ExprId,
    x: &[(Symbol, f64)],
    memo: &mut HashMap<ExprId, (f64, f64)>,
) -> (f64, f64) {
    if let Some(&r) = memo.get(&id) {
        return r;
    }
    let r = match g.node(id).clone() {
        Node::Const(bits) => {
            let c = f64::from_bits(bits);
            (c, 4.0 * U * c.abs())
        }
        Node::Input(s) => (x.iter().find(|(t, _)| *t == s).expect("bound").1, 0.0),
        Node::Add(ts) => {
            let (mut v, mut e) = (0.0, 0.0);
            for t in ts {
                let (a, ea) = graph_error_bound(g, t, x, memo);
                v += a;
                e += ea + U * v.abs();
            }
            (v, e)
        }
        Node::Mul(fs) => {
            let (mut v, mut e) = (1.0, 0.0);
            for f in fs {
                let (a, ea) = graph_error_bound(g, f, x, memo);
                let nv: f64 = v * a;
                e = v.abs() * ea + a.abs() * e + e * ea + U * nv.abs();
                v = nv;
            }
            (v, e)
        }
        Node::Pow(b, n) => {
            let (a, ea) = graph_error_bound(g, b, x, memo);
            let v = a.powi(n);
            let k = f64::from(n.unsigned_abs());
            let e = if ea >= 0.25 * a.abs() / k {
                f64::INFINITY
            } else {
                2.0 * k * v.abs() / a.abs() * ea + 2.0 * k * U * v.abs()
            };
            (v, e)
        }
        Node::Call(f, a) => {
            let (a, ea) = graph_error_bound(g, a, x, memo);
            match f.name() {
                "sqrt" => {
                    let v = a.sqrt();
                    (v, (a + ea).sqrt() - (a - ea).max(0.0).sqrt() + U * v.abs())
                }
                "exp" => {
                    let v = a.exp();
                    (v, v * ea.exp_m1() + 2.0 * U * v)
                }
                "sin" => (a.sin(), ea + 2.0 * U),
                _ => (a.cos(), ea + 2.0 * U),
            }
        }
    };
    memo.insert(id, r);
    r
}

fn bindings(g: &mut Graph, x: &[f64]) -> (Env, Vec<(Symbol, f64)>) {
    let mut e = Env::default();
    let mut list = Vec::new();
    for (i, &v) in x.iter().enumerate() {
        e.set(g, VARS[i], v);
        list.push((g.symbol(VARS[i]), v));
    }
    (e, list)
}

/// General constants for value tests (not exactly representable sums, so folding rounds).
const GENERAL_CONSTS: [f64; 8] = [0.1, 0.7, 1.3, 2.0, 3.0, -0.25, -1.7, 0.5];

/// Simplification preserves value: every random expression evaluates (through the simplified
/// graph) to its directly evaluated reference within the two rounding-error bounds.
mod cse;
mod diff;
mod dual;
mod simplify;
mod solve;

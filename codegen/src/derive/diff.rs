//! Symbolic differentiation.
//!
//! [`derivative`] takes the *total* derivative along a direction given by the rates of the input
//! symbols: `rates[s]` is ds/dt for each symbol that varies, every other symbol is constant. A
//! partial derivative is the special case of one symbol with rate 1. Rates let the model state
//! time-dependent basis functions (cos θ with d(cos θ)/dτ = −η sin θ, the damped basis EC, ES of
//! `docs/MODEL.md` §4) as plain symbols, so derivatives stay in closed form without trigonometry.

use std::collections::HashMap;

use crate::expr::{ExprId, Func, Graph, Node, Symbol};

/// d(`id`)/dt where each symbol `s` has rate `rates[s]` (symbols not in `rates` are constant).
pub fn derivative(g: &mut Graph, id: ExprId, rates: &HashMap<Symbol, ExprId>) -> ExprId {
    let mut memo = HashMap::new();
    diff_memo(g, id, rates, &mut memo)
}

/// The partial derivative ∂(`id`)/∂`s`.
pub fn partial(g: &mut Graph, id: ExprId, s: Symbol) -> ExprId {
    let one = g.constant(1.0);
    derivative(g, id, &HashMap::from([(s, one)]))
}

/// The `n`-th total derivative.
pub fn nth_derivative(
    g: &mut Graph,
    id: ExprId,
    rates: &HashMap<Symbol, ExprId>,
    n: usize,
) -> ExprId {
    (0..n).fold(id, |e, _| derivative(g, e, rates))
}

fn diff_memo(
    g: &mut Graph,
    id: ExprId,
    rates: &HashMap<Symbol, ExprId>,
    memo: &mut HashMap<ExprId, ExprId>,
) -> ExprId {
    if let Some(&d) = memo.get(&id) {
        return d;
    }
    let d = match g.node(id).clone() {
        Node::Const(_) => g.constant(0.0),
        Node::Input(s) => match rates.get(&s) {
            Some(&r) => r,
            None => g.constant(0.0),
        },
        Node::Add(ts) => {
            let ds: Vec<_> = ts.iter().map(|&t| diff_memo(g, t, rates, memo)).collect();
            g.sum(&ds)
        }
        Node::Mul(fs) => {
            // Product rule: Σ_i f_i' Π_{j≠i} f_j.
            let mut terms = Vec::with_capacity(fs.len());
            for i in 0..fs.len() {
                let di = diff_memo(g, fs[i], rates, memo);
                if g.is_const(di, 0.0) {
                    continue;
                }
                let mut factors: Vec<_> = fs
                    .iter()
                    .enumerate()
                    .filter(|&(j, _)| j != i)
                    .map(|(_, &f)| f)
                    .collect();
                factors.push(di);
                terms.push(g.product(&factors));
            }
            g.sum(&terms)
        }
        Node::Pow(b, n) => {
            // (bⁿ)' = n bⁿ⁻¹ b'.
            let db = diff_memo(g, b, rates, memo);
            let p = g.powi(b, n - 1);
            let k = g.constant(f64::from(n));
            g.product(&[k, p, db])
        }
        Node::Call(f, a) => {
            let da = diff_memo(g, a, rates, memo);
            let outer = match f {
                // (√a)' = a' / (2√a).
                Func::Sqrt => {
                    let inv = g.powi(id, -1);
                    g.scale(0.5, inv)
                }
                Func::Exp => id,
                Func::Sin => g.cos(a),
                Func::Cos => {
                    let s = g.sin(a);
                    g.neg(s)
                }
            };
            g.mul(outer, da)
        }
    };
    memo.insert(id, d);
    d
}

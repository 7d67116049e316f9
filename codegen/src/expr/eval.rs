//! Numeric evaluation of expressions, for tests and for checking derivations.

use std::collections::HashMap;

use super::{ExprId, Graph, Node, Symbol};

/// Values of input symbols.
#[derive(Clone, Debug, Default)]
pub struct Env(pub HashMap<Symbol, f64>);

impl Env {
    /// Bind the symbol named `name` in `graph` to `value`.
    pub fn set(&mut self, graph: &mut Graph, name: &str, value: f64) -> &mut Self {
        let s = graph.symbol(name);
        self.0.insert(s, value);
        self
    }
}

impl Graph {
    /// Evaluate `id` with `env`; unbound inputs evaluate to NaN.
    pub fn eval(&self, id: ExprId, env: &Env) -> f64 {
        let mut memo = HashMap::new();
        self.eval_memo(id, env, &mut memo)
    }

    fn eval_memo(&self, id: ExprId, env: &Env, memo: &mut HashMap<ExprId, f64>) -> f64 {
        if let Some(&v) = memo.get(&id) {
            return v;
        }
        let v = match self.node(id) {
            Node::Const(bits) => f64::from_bits(*bits),
            Node::Input(s) => env.0.get(s).copied().unwrap_or(f64::NAN),
            Node::Add(ts) => ts.iter().map(|&t| self.eval_memo(t, env, memo)).sum(),
            Node::Mul(fs) => fs.iter().map(|&f| self.eval_memo(f, env, memo)).product(),
            Node::Pow(b, n) => self.eval_memo(*b, env, memo).powi(*n),
            Node::Call(f, a) => f.apply(self.eval_memo(*a, env, memo)),
        };
        memo.insert(id, v);
        v
    }
}

//! Common-subexpression elimination into straight-line code, and operation counts.
//!
//! Interning already shares every repeated sub-expression; CSE decides which shared nodes get a
//! `let` binding (every non-leaf node used twice or more, and every base of a power that is
//! emitted as repeated multiplication) and orders the bindings topologically.

use std::collections::{BTreeSet, HashMap};
use std::fmt;
use std::ops::AddAssign;

use crate::expr::{ExprId, Func, Graph, Node};

/// Arithmetic operation counts of emitted code.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCounts {
    /// Additions and subtractions.
    pub add: u64,
    /// Multiplications.
    pub mul: u64,
    /// Divisions.
    pub div: u64,
    /// Square roots.
    pub sqrt: u64,
    /// exp, sin and cos calls.
    pub transcendental: u64,
}

impl AddAssign for OpCounts {
    fn add_assign(&mut self, o: Self) {
        self.add = self.add.saturating_add(o.add);
        self.mul = self.mul.saturating_add(o.mul);
        self.div = self.div.saturating_add(o.div);
        self.sqrt = self.sqrt.saturating_add(o.sqrt);
        self.transcendental = self.transcendental.saturating_add(o.transcendental);
    }
}

impl fmt::Display for OpCounts {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{:>5} add {:>5} mul {:>4} div {:>3} sqrt {:>3} trans",
            self.add, self.mul, self.div, self.sqrt, self.transcendental
        )
    }
}

/// The straight-line plan of one function: bindings in evaluation order.
pub struct Plan {
    /// Nodes bound by `let`, in evaluation order.
    pub bindings: Vec<ExprId>,
    /// Products c·M with a power-of-two coefficient c < 0 whose magnitude M (the product of the
    /// other factors) is itself a node: they are written as |c|·M (M shared with its other
    /// uses, so that a force that enters one output with + and another with − is computed
    /// once). Scaling by a power of two is exact, so the value is the same to the bit.
    pub negated: HashMap<ExprId, (f64, ExprId)>,
    /// Binding index of each bound node.
    pub temp_index: HashMap<ExprId, usize>,
    /// Operation counts if every output were evaluated as a tree (no sharing).
    pub before: OpCounts,
}

/// Plan the evaluation of `outputs`.
pub fn plan(g: &Graph, outputs: &[ExprId]) -> Plan {
    let mut uses: HashMap<ExprId, usize> = HashMap::new();
    let mut forced: BTreeSet<ExprId> = BTreeSet::new();
    let mut order = Vec::new();
    let mut visited = BTreeSet::new();
    let mut negated = HashMap::new();
    let mut walk = Walk {
        g,
        uses: &mut uses,
        forced: &mut forced,
        visited: &mut visited,
        order: &mut order,
        negated: &mut negated,
    };
    for &o in outputs {
        *walk.uses.entry(o).or_insert(0) += 1;
        walk.visit(o);
    }
    let is_leaf = |id: ExprId| matches!(g.node(id), Node::Const(_) | Node::Input(_));
    let bindings: Vec<ExprId> = order
        .iter()
        .copied()
        .filter(|&id| !is_leaf(id) && (uses[&id] >= 2 || forced.contains(&id)))
        .collect();
    let temp_index = bindings
        .iter()
        .enumerate()
        .map(|(k, &id)| (id, k))
        .collect();
    let mut memo = HashMap::new();
    let mut before = OpCounts::default();
    for &o in outputs {
        before += tree_ops(g, o, &mut memo);
    }
    Plan {
        bindings,
        temp_index,
        negated,
        before,
    }
}

/// The magnitude of a product c·M (c < 0 a power of two, M the product of the other factors,
/// at least two) when M is an interned node.
fn magnitude(g: &Graph, id: ExprId) -> Option<(f64, ExprId)> {
    let Node::Mul(fs) = g.node(id) else {
        return None;
    };
    let mut coefficient = None;
    let mut rest = Vec::with_capacity(fs.len());
    for &f in fs {
        match g.as_const(f) {
            Some(c) => coefficient = Some(c),
            None => rest.push(f),
        }
    }
    let c = coefficient?;
    let power_of_two = c < 0.0 && (-c).log2().fract() == 0.0;
    if !power_of_two || rest.len() < 2 {
        return None;
    }
    g.lookup(&Node::Mul(rest)).map(|m| (c, m))
}

/// The depth-first walk counting each node's uses.
struct Walk<'a> {
    g: &'a Graph,
    uses: &'a mut HashMap<ExprId, usize>,
    forced: &'a mut BTreeSet<ExprId>,
    visited: &'a mut BTreeSet<ExprId>,
    order: &'a mut Vec<ExprId>,
    negated: &'a mut HashMap<ExprId, (f64, ExprId)>,
}

impl Walk<'_> {
    fn visit(&mut self, id: ExprId) {
        if !self.visited.insert(id) {
            return;
        }
        if let Some((c, m)) = magnitude(self.g, id) {
            // Written as |c|·M: one use of M instead of its factors.
            self.negated.insert(id, (c, m));
            *self.uses.entry(m).or_insert(0) += 1;
            self.visit(m);
            self.order.push(id);
            return;
        }
        for c in self.g.children(id) {
            *self.uses.entry(c).or_insert(0) += 1;
            if matches!(self.g.node(id), Node::Pow(_, n) if n.abs() >= 2) {
                self.forced.insert(c);
            }
            self.visit(c);
        }
        self.order.push(id);
    }
}

/// Operations of `id` evaluated as a tree (no sharing), as the emitter would write it with no
/// bindings: a power's base is repeated, a product's factors multiplied and divided.
fn tree_ops(g: &Graph, id: ExprId, memo: &mut HashMap<ExprId, OpCounts>) -> OpCounts {
    if let Some(&c) = memo.get(&id) {
        return c;
    }
    let mut c = OpCounts::default();
    match g.node(id).clone() {
        Node::Const(_) | Node::Input(_) => {}
        Node::Add(ts) => {
            c.add = ts.len() as u64 - 1;
            for t in ts {
                c += tree_ops(g, t, memo);
            }
        }
        Node::Mul(fs) => {
            let (mut num, mut den) = (0u64, 0u64);
            for f in fs {
                match g.node(f).clone() {
                    Node::Const(bits) => num += u64::from(f64::from_bits(bits).abs() != 1.0),
                    Node::Pow(b, n) => {
                        let k = u64::from(n.unsigned_abs());
                        if n < 0 {
                            den += k
                        } else {
                            num += k
                        }
                        let base = tree_ops(g, b, memo);
                        for _ in 0..k {
                            c += base;
                        }
                    }
                    _ => {
                        num += 1;
                        c += tree_ops(g, f, memo);
                    }
                }
            }
            c.mul += num.saturating_sub(1) + den.saturating_sub(1);
            c.div += u64::from(den > 0);
        }
        Node::Pow(b, n) => {
            let k = u64::from(n.unsigned_abs());
            c.mul = k - 1;
            c.div = u64::from(n < 0);
            let base = tree_ops(g, b, memo);
            for _ in 0..k {
                c += base;
            }
        }
        Node::Call(f, a) => {
            if f == Func::Sqrt {
                c.sqrt = 1
            } else {
                c.transcendental = 1
            }
            c += tree_ops(g, a, memo);
        }
    }
    memo.insert(id, c);
    c
}

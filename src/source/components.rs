//! The component graph of a font: which glyph each component uses, the cycles, and an
//! order with every glyph after the glyphs it uses (for sizes computed once per glyph).
//!
//! Linear in glyphs plus components: one name lookup per component and one iterative
//! Tarjan pass for the strongly connected components (iterative, so a 100,000-deep chain
//! of components needs no deep call stack). A component is on a cycle exactly when its
//! glyph and its base are in the same strongly connected component.

use std::collections::HashMap;

use super::diagnostic::Diagnostics;
use super::load::GlyphFile;

/// Components resolved to glyph indices, with strongly connected components.
pub(super) struct ComponentGraph {
    /// Per glyph, per component: the index of its base, `None` when no glyph has that name.
    pub bases: Vec<Vec<Option<usize>>>,
    /// Glyph indices, each glyph after every glyph it reaches (cycles excepted).
    pub order: Vec<usize>,
    /// Per glyph: the id of its strongly connected component.
    scc: Vec<usize>,
}

impl ComponentGraph {
    pub fn new(glyphs: &[GlyphFile]) -> Self {
        let mut index: HashMap<&str, usize> = HashMap::with_capacity(glyphs.len());
        for (i, g) in glyphs.iter().enumerate() {
            index.entry(g.glyph.name.as_str()).or_insert(i);
        }
        let bases: Vec<Vec<Option<usize>>> = glyphs
            .iter()
            .map(|g| {
                let bases = g.glyph.components.iter();
                bases.map(|c| index.get(c.base.as_str()).copied()).collect()
            })
            .collect();
        let (scc, order) = tarjan(&bases);
        ComponentGraph { bases, order, scc }
    }

    /// Whether component `k` of glyph `g` leads back to `g` (directly or through others).
    pub fn on_cycle(&self, g: usize, k: usize) -> bool {
        self.bases[g][k].is_some_and(|b| self.scc[b] == self.scc[g])
    }

    /// Whether glyph `g` has a component on a cycle.
    pub fn in_cycle(&self, g: usize) -> bool {
        (0..self.bases[g].len()).any(|k| self.on_cycle(g, k))
    }
}

/// Strongly connected component ids, and the glyphs in the order Tarjan's algorithm
/// completes them (every glyph after the glyphs it reaches outside its own component).
fn tarjan(bases: &[Vec<Option<usize>>]) -> (Vec<usize>, Vec<usize>) {
    const UNSEEN: usize = usize::MAX;
    let n = bases.len();
    let mut number = vec![UNSEEN; n];
    let mut low = vec![0; n];
    let mut on_stack = vec![false; n];
    let mut stack = Vec::new();
    let mut scc = vec![UNSEEN; n];
    let mut order = Vec::with_capacity(n);
    let mut next = 0;
    let mut scc_count = 0;
    // Depth-first search frames: (glyph, index of the next component to follow).
    let mut frames: Vec<(usize, usize)> = Vec::new();
    for root in 0..n {
        if number[root] != UNSEEN {
            continue;
        }
        frames.push((root, 0));
        while let Some(&mut (v, ref mut k)) = frames.last_mut() {
            if *k == 0 && number[v] == UNSEEN {
                number[v] = next;
                low[v] = next;
                next += 1;
                stack.push(v);
                on_stack[v] = true;
            }
            if let Some(edge) = bases[v].get(*k) {
                *k += 1;
                let Some(w) = *edge else { continue };
                if number[w] == UNSEEN {
                    frames.push((w, 0));
                } else if on_stack[w] {
                    low[v] = low[v].min(number[w]);
                }
                continue;
            }
            frames.pop();
            if let Some(&(parent, _)) = frames.last() {
                low[parent] = low[parent].min(low[v]);
            }
            if low[v] == number[v] {
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    scc[w] = scc_count;
                    order.push(w);
                    if w == v {
                        break;
                    }
                }
                scc_count += 1;
            }
        }
    }
    (scc, order)
}

/// Components whose base does not exist, and components on a cycle.
pub(super) fn check_components(
    glyphs: &[GlyphFile],
    graph: &ComponentGraph,
    out: &mut Diagnostics,
) {
    for (g, file) in glyphs.iter().enumerate() {
        if file.glyph.components.is_empty() {
            continue;
        }
        let mut ctx = file.ctx(out);
        let components = file.glyph.components.iter().zip(&file.spans.bases);
        for (k, (c, &off)) in components.enumerate() {
            if graph.bases[g][k].is_none() {
                ctx.err(off, format!("component base `{}` does not exist", c.base));
            } else if graph.on_cycle(g, k) {
                ctx.err(
                    off,
                    format!(
                        "component cycle: `{}` uses `{}`, which leads back to it",
                        file.glyph.name, c.base
                    ),
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::tarjan;

    #[test]
    fn cycles_and_order() {
        // 0 -> 1 -> 2 -> 1 (cycle 1-2), 3 -> 0, 4 -> 4 (self), 5 -> missing.
        let bases = vec![
            vec![Some(1)],
            vec![Some(2)],
            vec![Some(1)],
            vec![Some(0)],
            vec![Some(4)],
            vec![None],
        ];
        let (scc, order) = tarjan(&bases);
        assert_eq!(scc[1], scc[2]);
        assert_ne!(scc[0], scc[1]);
        assert_ne!(scc[3], scc[0]);
        let pos = |g: usize| order.iter().position(|&x| x == g).unwrap();
        assert!(pos(2) < pos(0) && pos(1) < pos(0) && pos(0) < pos(3));
        assert_eq!(order.len(), 6);
    }

    #[test]
    fn a_deep_chain_needs_no_deep_stack() {
        let n = 200_000;
        let bases: Vec<Vec<Option<usize>>> = (0..n)
            .map(|i| if i == 0 { vec![] } else { vec![Some(i - 1)] })
            .collect();
        let (scc, order) = tarjan(&bases);
        assert_eq!(order, (0..n).collect::<Vec<_>>());
        assert!(scc.iter().enumerate().all(|(i, &s)| s == i));
    }
}

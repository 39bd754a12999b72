//! Vertex addresses without folds: [`screen_addresses`] rounds each projected vertex to the
//! nearest integer address and repairs the faces that rounding folds over (the argument is in its
//! doc comment), so a back-face-culled convex mesh is written exactly once.

use std::collections::HashMap;

use glam::DVec2;

use super::camera::Camera;
use super::mesh::Mesh;
use crate::types::MAX_ADDRESS;

/// Integer screen addresses of every mesh vertex: the continuous screen positions rounded to the
/// nearest integer, then *repaired* where rounding folds the projected surface over itself.
///
/// Why. Rounding moves each vertex by up to half a pixel. That can reverse the orientation of a
/// sub-pixel-thin triangle (at the silhouette, where faces are seen edge-on, and in the slivers
/// around a sphere's poles). The projected surface then folds: two front faces cover the same
/// pixels, and a back-face-culled convex mesh is no longer written exactly once.
///
/// What makes coverage exact. Let D be the faces drawn (negative area in mesh order, see
/// [`project`]), plus the zero-area faces that are front faces before rounding (they cover no
/// pixel). At any sample point, the number of faces of D covering it equals the winding number
/// of the boundary of D (its directed edges whose reverse is not in D) around it, whatever the
/// vertex positions; the fill convention makes that hold pixel by pixel. So each pixel is
/// written at most once exactly when that boundary winds 0 or 1 times around every pixel centre,
/// and the repair below runs exactly when plain rounding would write some pixel twice.
///
/// Repair. Only for views whose continuous projection is single-layer (the boundary of the
/// continuous front faces winds 0 or 1 times around every pixel centre: any convex mesh, e.g.
/// the sphere; a non-convex mesh that overlaps itself keeps plain rounding, and the depth buffer
/// resolves its overlaps). In passes, while the rounded boundary winds otherwise around some
/// pixel centre (`overlaps` finds the row spans and the two boundary edges bounding each),
/// every *broken* face (rounded to the other orientation than before rounding) on either side
/// of those edges is mended:
/// 1. *re-snap*: one of its vertices rounds the other way in x, in y or both (a corner of the
///    unit cell holding its continuous position): the corner nearest that position that mends
///    the face and breaks no other face around that vertex (among its three vertices, the
///    smallest move wins); each re-snap lowers the number of broken faces;
/// 2. if no such move exists, its shortest edge *collapses*: both end vertices (with every
///    vertex already merged with them) take one address, that of whichever end is nearer the
///    mean of their continuous positions; each collapse lowers the number of vertex groups.
///
/// A pass that finds no broken face collapses the shorter of its first span's two boundary
/// edges instead. Every step lowers (vertex groups, broken faces) lexicographically, so the
/// loop ends.
///
/// Vertices with bit-identical model positions (OBJ seams) start in one group, so the repair
/// never opens a crack between them. Where rounding folds nothing (e.g. the default scene) the
/// result is exactly the rounded positions; otherwise a vertex only ever moves to a corner of its
/// own unit cell or to the address of a vertex it is merged with. Addresses stay in 0..=4095 when the rounded
/// ones are; [`project`] checks the 12-bit range. The mesh must be valid ([`Mesh::validate`]:
/// indices in range, finite positions), as [`project`] ensures before calling this.
///
/// [`project`]: super::project
pub fn screen_addresses(mesh: &Mesh, camera: &Camera) -> Vec<DVec2> {
    let exact: Vec<DVec2> = mesh
        .positions
        .iter()
        .map(|&p| camera.screen(p).truncate())
        .collect();
    Snapper::new(mesh, exact).run()
}

/// Working state of [`screen_addresses`]: a union-find over vertices with, per group (root), the
/// sum and count of the continuous positions, the current address and the incident faces.
struct Snapper<'m> {
    tris: &'m [[u32; 3]],
    exact: Vec<DVec2>,
    /// Whether each face is a front face before rounding.
    front: Vec<bool>,
    parent: Vec<usize>,
    sum: Vec<DVec2>,
    count: Vec<f64>,
    addr: Vec<DVec2>,
    incident: Vec<Vec<usize>>,
}

/// A directed boundary edge between two vertex groups, and the face of D it belongs to.
struct BoundaryEdge {
    ends: [usize; 2],
    face: usize,
}

fn area2(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Every span of a pixel-centre row (y = r + 0.5) that holds a pixel centre around which the
/// closed chain of directed `edges` winds other than 0 or 1 times, as the indices of the two
/// edges bounding it. Winding counts +1 for each edge crossed going down the screen (y
/// increasing), −1 going up, sweeping from the left; a front face (negative area) alone winds
/// +1. For integer end points the crossings, and so the tie with a centre lying exactly on an
/// edge, are computed exactly.
fn overlaps(edges: &[[DVec2; 2]]) -> Vec<[usize; 2]> {
    // Rows r with r + 0.5 inside the 12-bit range (and one beyond); edges bucketed per row.
    let row = |y: f64| (y - 0.5).clamp(-2.0, MAX_ADDRESS as f64 + 2.0);
    let (r0, r1) = (-1i64, MAX_ADDRESS as i64 + 1);
    let mut rows: Vec<Vec<usize>> = vec![Vec::new(); (r1 - r0 + 1) as usize];
    for (k, &[a, b]) in edges.iter().enumerate() {
        if a.y == b.y || !(a.y.is_finite() && b.y.is_finite()) {
            continue;
        }
        let (lo, hi) = (
            row(a.y.min(b.y)).ceil() as i64,
            row(a.y.max(b.y)).floor() as i64,
        );
        for r in lo.max(r0)..=hi.min(r1) {
            rows[(r - r0) as usize].push(k);
        }
    }
    let mut xs: Vec<(f64, i32, usize)> = Vec::new();
    let mut found = Vec::new();
    for (i, ks) in rows.iter().enumerate() {
        let y = (r0 + i as i64) as f64 + 0.5;
        xs.clear();
        for &k in ks {
            let [a, b] = edges[k];
            if (a.y <= y) != (b.y <= y) {
                // From the upper end, so that a segment and its reverse cross at the same x.
                let (p, q) = if a.y < b.y { (a, b) } else { (b, a) };
                let x = p.x + (y - p.y) * (q.x - p.x) / (q.y - p.y);
                xs.push((x, if a.y < b.y { 1 } else { -1 }, k));
            }
        }
        xs.sort_by(|p, q| p.0.total_cmp(&q.0));
        let mut w = 0;
        for j in 0..xs.len() {
            w += xs[j].1;
            // The span [x_j, x_j+1) holds a pixel centre c + 0.5 (a centre exactly on a
            // crossing belongs to the span on its right, as the fill convention has it).
            let holds_centre = j + 1 < xs.len() && (xs[j].0 - 0.5).ceil() + 0.5 < xs[j + 1].0;
            if holds_centre && !(0..=1).contains(&w) {
                found.push([xs[j].2, xs[j + 1].2]);
            }
        }
    }
    found
}

impl<'m> Snapper<'m> {
    fn new(mesh: &'m Mesh, exact: Vec<DVec2>) -> Self {
        let n = exact.len();
        let front = mesh
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| exact[i as usize]);
                area2(a, b, c) < 0.0
            })
            .collect();
        let mut incident = vec![Vec::new(); n];
        for (k, t) in mesh.triangles.iter().enumerate() {
            for &i in t {
                incident[i as usize].push(k);
            }
        }
        let mut s = Snapper {
            tris: &mesh.triangles,
            front,
            parent: (0..n).collect(),
            addr: exact.iter().map(|p| p.round()).collect(),
            sum: exact.clone(),
            exact,
            count: vec![1.0; n],
            incident,
        };
        let mut seen: HashMap<[u64; 3], usize> = HashMap::new();
        for (i, p) in mesh.positions.iter().enumerate() {
            match seen.entry(p.to_array().map(f64::to_bits)) {
                std::collections::hash_map::Entry::Occupied(e) => s.union(*e.get(), i),
                std::collections::hash_map::Entry::Vacant(e) => {
                    e.insert(i);
                }
            }
        }
        s
    }

    fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return;
        }
        self.parent[rb] = ra;
        let (s, c) = (self.sum[rb], self.count[rb]);
        self.sum[ra] += s;
        self.count[ra] += c;
        let mean = self.sum[ra] / self.count[ra];
        if self.addr[rb].distance_squared(mean) < self.addr[ra].distance_squared(mean) {
            self.addr[ra] = self.addr[rb];
        }
        let moved = std::mem::take(&mut self.incident[rb]);
        self.incident[ra].extend(moved);
    }

    fn groups(&mut self, t: usize) -> [usize; 3] {
        self.tris[t].map(|i| self.find(i as usize))
    }

    /// Whether face `t` is broken with group `g` placed at `at` (the others where they are): a
    /// front face rounded to a back face, or the reverse.
    fn broken_with(&mut self, t: usize, g: usize, at: DVec2) -> bool {
        let p = self
            .groups(t)
            .map(|r| if r == g { at } else { self.addr[r] });
        let a = area2(p[0], p[1], p[2]);
        if self.front[t] {
            a > 0.0
        } else {
            a < 0.0
        }
    }

    fn broken(&mut self, t: usize) -> bool {
        let g = self.find(self.tris[t][0] as usize);
        let at = self.addr[g];
        self.broken_with(t, g, at)
    }

    /// Whether face `t` belongs to D: drawn, or of zero area and a front face before rounding.
    fn in_chain(&mut self, t: usize, rounded: bool) -> bool {
        if !rounded {
            return self.front[t];
        }
        let p = self.groups(t).map(|g| self.addr[g]);
        let a = area2(p[0], p[1], p[2]);
        a < 0.0 || (a == 0.0 && self.front[t])
    }

    /// The boundary of D (rounded addresses, or the continuous positions), in a fixed order.
    fn boundary(&mut self, rounded: bool) -> Vec<BoundaryEdge> {
        let mut count: HashMap<[usize; 2], (i32, usize)> = HashMap::new();
        for t in 0..self.tris.len() {
            if !self.in_chain(t, rounded) {
                continue;
            }
            let r = self.groups(t);
            for k in 0..3 {
                let e = [r[k], r[(k + 1) % 3]];
                if e[0] != e[1] {
                    count.entry(e).or_insert((0, t)).0 += 1;
                }
            }
        }
        let mut out = Vec::new();
        for (&[u, v], &(n, face)) in &count {
            let m = n - count.get(&[v, u]).map_or(0, |c| c.0);
            for _ in 0..m.max(0) {
                out.push(BoundaryEdge { ends: [u, v], face });
            }
        }
        out.sort_by_key(|e| (e.ends, e.face));
        out
    }

    fn segments(&self, edges: &[BoundaryEdge], rounded: bool) -> Vec<[DVec2; 2]> {
        let pos = if rounded { &self.addr } else { &self.exact };
        edges.iter().map(|e| e.ends.map(|g| pos[g])).collect()
    }

    /// The nearest address to the group's continuous position, among the four corners of the
    /// unit cell holding it (so no coordinate moves by a pixel or more), that mends `t` and
    /// breaks no other face of the group, with its distance.
    fn resnap(&mut self, t: usize, g: usize) -> Option<(f64, DVec2)> {
        let here = self.addr[g];
        let centre = self.sum[g] / self.count[g];
        let in_range = |p: DVec2| {
            (0.0..=MAX_ADDRESS as f64).contains(&p.x) && (0.0..=MAX_ADDRESS as f64).contains(&p.y)
        };
        let (lo, hi) = (centre.floor(), centre.ceil());
        let mut candidates: Vec<DVec2> = [(lo.x, lo.y), (hi.x, lo.y), (lo.x, hi.y), (hi.x, hi.y)]
            .into_iter()
            .map(|(x, y)| DVec2::new(x, y))
            .filter(|&p| p != here && (in_range(p) || !in_range(here)))
            .collect();
        candidates.sort_by(|a, b| a.distance(centre).total_cmp(&b.distance(centre)));
        candidates.dedup();
        let around = self.incident[g].clone();
        candidates.into_iter().find_map(|at| {
            let ok =
                !self.broken_with(t, g, at) && around.iter().all(|&u| !self.broken_with(u, g, at));
            ok.then(|| (at.distance(centre), at))
        })
    }

    /// Mends broken face `t`: a re-snap if one exists, else the collapse of its shortest edge.
    fn mend(&mut self, t: usize) {
        let groups = self.groups(t);
        let best = groups
            .iter()
            .filter_map(|&g| self.resnap(t, g).map(|(d, at)| (d, g, at)))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((_, g, at)) = best {
            self.addr[g] = at;
            return;
        }
        let p = groups.map(|g| self.addr[g]);
        let (a, b) = [(0, 1), (1, 2), (2, 0)]
            .into_iter()
            .min_by(|&(a, b), &(c, d)| {
                p[a].distance_squared(p[b])
                    .total_cmp(&p[c].distance_squared(p[d]))
            })
            .expect("three edges");
        self.union(groups[a], groups[b]);
    }

    /// One repair pass; false when the rounded boundary of D winds 0 or 1 times everywhere.
    /// Every broken face beside an offending span is mended (state is re-read face by face);
    /// only if none was broken does the first span's shorter boundary edge collapse.
    fn mend_folds(&mut self) -> bool {
        let edges = self.boundary(true);
        let segments = self.segments(&edges, true);
        let spans = overlaps(&segments);
        if spans.is_empty() {
            return false;
        }
        let mut mended = false;
        let mut seen = std::collections::HashSet::new();
        for pair in &spans {
            // The faces on both sides of the two edges: the face of D, and the faces across.
            for &k in pair {
                if !seen.insert(k) {
                    continue;
                }
                // Earlier mends of this pass may have merged groups.
                let [u, v] = edges[k].ends.map(|g| self.find(g));
                let mut suspects = vec![edges[k].face];
                for t in self.incident[v].clone() {
                    let r = self.groups(t);
                    if (0..3).any(|i| r[i] == v && r[(i + 1) % 3] == u) {
                        suspects.push(t);
                    }
                }
                for t in suspects {
                    if self.broken(t) {
                        self.mend(t);
                        mended = true;
                    }
                }
            }
        }
        if !mended {
            let pair = spans[0];
            let length = |k: usize| segments[k][0].distance(segments[k][1]);
            let k = if length(pair[0]) <= length(pair[1]) {
                pair[0]
            } else {
                pair[1]
            };
            // A crossing edge has distinct end addresses, so its ends are in distinct groups.
            self.union(edges[k].ends[0], edges[k].ends[1]);
        }
        true
    }

    fn run(mut self) -> Vec<DVec2> {
        let continuous = self.boundary(false);
        if overlaps(&self.segments(&continuous, false)).is_empty() {
            while self.mend_folds() {}
        }
        (0..self.parent.len())
            .map(|i| {
                let r = self.find(i);
                self.addr[r]
            })
            .collect()
    }
}

//! Distance maps over a grid's nodes: how far every node is from the nearest node of a mask
//! (the centres a tool may take, the material only a smaller tool reaches, a part's
//! silhouette), by the lower envelope of parabolas that seed 000's reach maps use.

/// The Euclidean distance from every node of an `nx × ny` grid of `spacing` to the nearest node
/// where `inside` holds (+∞ with none): down the columns by two sweeps, then along the rows by
/// the lower envelope of parabolas (Felzenszwalb and Huttenlocher); what a tool reaches around
/// the centres it may take.
pub fn distance_to(inside: &[bool], nx: usize, ny: usize, spacing: f64) -> Vec<f64> {
    distance_within(inside, nx, ny, spacing, f64::INFINITY)
}

/// [`distance_to`] where it is no more than `cap`, +∞ beyond: the same distances there, with
/// only the rows within `cap` of a node inside worked through (where only "within reach"
/// is asked and what is looked for is sparse, most rows are not).
///
/// A node's nearest node inside is no farther down its column than from the node itself, so
/// dropping the column distances beyond `cap` keeps it wherever the distance is within `cap`.
pub fn distance_within(inside: &[bool], nx: usize, ny: usize, spacing: f64, cap: f64) -> Vec<f64> {
    distance_within_rows(inside, nx, ny, spacing, cap, 0..ny)
}

/// [`distance_within`] at the rows `rows` only (`nx` a row, from the first of them): the
/// others' nodes still count as inside where they are, and only the rows asked for are worked
/// along (a window of the grid grown by the cap to hold what its distances need).
pub fn distance_within_rows(inside: &[bool], nx: usize, ny: usize, spacing: f64, cap: f64, rows: std::ops::Range<usize>) -> Vec<f64> {
    // Column distances (in nodes) past this one are dropped: a node past it lies farther than `cap`.
    let reach = (cap / spacing).floor() + 1.0;
    let rows = rows.start.min(ny)..rows.end.min(ny);
    // Along the columns the values are 0 and far, so the envelope's minimum is the squared
    // distance to the nearest node inside in the column: two sweeps down and up find it for all
    // columns at once, row by row (the same values: whole numbers, exact in f64).
    let mut d2 = vec![f64::INFINITY; nx * ny];
    for j in 0..ny {
        for i in 0..nx {
            let c = j * nx + i;
            d2[c] = if inside[c] {
                0.0
            } else if j > 0 {
                d2[c - nx] + 1.0
            } else {
                f64::INFINITY
            };
        }
    }
    // (Up as far as the first row asked for: the rows above it are not.)
    for j in (rows.start..ny.saturating_sub(1)).rev() {
        for i in 0..nx {
            let c = j * nx + i;
            d2[c] = d2[c].min(d2[c + nx] + 1.0);
        }
    }
    // Only the rows asked for go on from here.
    let mut d2 = d2.split_off(rows.start * nx);
    d2.truncate(rows.len() * nx);
    // A column with no node inside, or none within `cap`, stays far, and a row all far is left
    // out below: most of them where what is looked for is sparse, such as the material a rest
    // tool alone reaches.
    d2.iter_mut().for_each(|v| *v = if v.is_finite() && *v <= reach { *v * *v } else { FAR });
    let mut work = Envelope::default();
    for row in d2.chunks_exact_mut(nx.max(1)) {
        if row.iter().all(|&v| v >= FAR) {
            continue;
        }
        work.run(row);
        row.copy_from_slice(&work.out);
    }
    d2.into_iter().map(|v| if v >= FAR { f64::INFINITY } else { v.sqrt() * spacing }).map(|d| if d <= cap { d } else { f64::INFINITY }).collect()
}

/// Whether each node of an `nx × ny` grid of `spacing` lies within `cap` of one of the nodes
/// `marked` (indices): `distance_within(inside, …, cap)[n] <= cap` for the mask of those nodes,
/// the same comparison of the same whole-number squared distances, made by marking a disc of
/// nodes round each. Where the nodes are few (the material only a rest tool reaches, a few
/// dozen cells of a million) it passes over the rest of the grid.
pub fn near_any(marked: &[usize], nx: usize, ny: usize, spacing: f64, cap: f64) -> Vec<bool> {
    let mut near = vec![false; nx * ny];
    if marked.is_empty() || nx == 0 {
        return near;
    }
    // The disc's offsets: past `reach` nodes along a column, the distance is past the cap.
    let reach = (cap / spacing).floor().min(nx.max(ny) as f64) as i64 + 1;
    let disc: Vec<(i64, i64)> = (-reach..=reach).flat_map(|dj| (-reach..=reach).map(move |di| (di, dj))).filter(|&(di, dj)| ((di * di + dj * dj) as f64).sqrt() * spacing <= cap).collect();
    for &m in marked {
        let (mi, mj) = ((m % nx) as i64, (m / nx) as i64);
        for &(di, dj) in &disc {
            let (i, j) = (mi + di, mj + dj);
            if i >= 0 && j >= 0 && (i as usize) < nx && (j as usize) < ny {
                near[j as usize * nx + i as usize] = true;
            }
        }
    }
    near
}

/// A squared distance standing for none: beyond every distance a grid can hold.
const FAR: f64 = 1e20;

/// The squared distance transform along one line, `out[q] = min_p (q − p)² + f[p]`, with its
/// working space kept from line to line.
#[derive(Default)]
struct Envelope {
    out: Vec<f64>,
    /// The parabolas of the lower envelope, and the boundaries between them.
    v: Vec<usize>,
    z: Vec<f64>,
}

impl Envelope {
    fn run(&mut self, f: &[f64]) {
        let n = f.len();
        let (out, v, z) = (&mut self.out, &mut self.v, &mut self.z);
        out.clear();
        out.resize(n, FAR);
        v.clear();
        v.resize(n, 0);
        z.clear();
        z.resize(n + 1, 0.0);
        // Only the parabolas of the values under [`FAR`]: one of those is the lowest wherever
        // there is one (a far one lies above every other at any node of a line), and a far one
        // meets them at ±10¹⁹ or so, off the line: the envelope of the others is the same.
        let s = |q: usize, p: usize| ((f[q] + (q * q) as f64) - (f[p] + (p * p) as f64)) / (2.0 * (q as f64 - p as f64));
        let mut near = (0..n).filter(|&q| f[q] < FAR);
        let Some(first) = near.next() else { return };
        let mut k = 0;
        v[0] = first;
        z[0] = f64::NEG_INFINITY;
        z[1] = f64::INFINITY;
        for q in near {
            let mut x = s(q, v[k]);
            // z[0] is −∞, so the loop stops at k = 0 at the latest.
            while x <= z[k] {
                k -= 1;
                x = s(q, v[k]);
            }
            k += 1;
            v[k] = q;
            z[k] = x;
            z[k + 1] = f64::INFINITY;
        }
        k = 0;
        for (q, o) in out.iter_mut().enumerate() {
            while z[k + 1] < q as f64 {
                k += 1;
            }
            let p = v[k];
            *o = (q as f64 - p as f64).powi(2) + f[p];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The two passes of the envelope, as [`distance_to`] made them before its column sweeps.
    fn by_envelopes(inside: &[bool], nx: usize, ny: usize, spacing: f64) -> Vec<f64> {
        let far = FAR;
        let mut d2: Vec<f64> = inside.iter().map(|&b| if b { 0.0 } else { far }).collect();
        let mut work = Envelope::default();
        for i in 0..nx {
            if !(0..ny).any(|j| inside[j * nx + i]) {
                continue;
            }
            let line: Vec<f64> = (0..ny).map(|j| d2[j * nx + i]).collect();
            work.run(&line);
            (0..ny).for_each(|j| d2[j * nx + i] = work.out[j]);
        }
        for j in 0..ny {
            let row = &mut d2[j * nx..(j + 1) * nx];
            if row.iter().any(|&v| v < far) {
                work.run(row);
                row.copy_from_slice(&work.out);
            }
        }
        d2.into_iter().map(|v| if v >= far { f64::INFINITY } else { v.sqrt() * spacing }).collect()
    }

    #[test]
    fn column_sweeps_give_the_envelopes_distances_bit_for_bit() {
        let mut rng = crate::offset::check::Rng::new(38);
        for case in 0..200 {
            let (nx, ny) = (1 + rng.below(90), 1 + rng.below(90));
            // Sparse to dense masks, and blobs: discs of nodes.
            let density = [0.0, 0.002, 0.02, 0.3, 0.9, 1.0][case % 6];
            let mut inside: Vec<bool> = (0..nx * ny).map(|_| rng.next_f64() < density).collect();
            if case % 7 == 0 {
                let (ci, cj, r) = (rng.range(0.0, nx as f64), rng.range(0.0, ny as f64), rng.range(1.0, 30.0));
                (0..nx * ny).for_each(|c| inside[c] |= ((c % nx) as f64 - ci).hypot((c / nx) as f64 - cj) <= r);
            }
            let (fast, slow) = (distance_to(&inside, nx, ny, 0.37), by_envelopes(&inside, nx, ny, 0.37));
            for c in 0..nx * ny {
                assert_eq!(fast[c].to_bits(), slow[c].to_bits(), "case {case} ({nx} × {ny}), node {c}");
            }
        }
    }

    #[test]
    fn capped_distances_are_the_distances_within_the_cap() {
        let mut rng = crate::offset::check::Rng::new(51);
        for case in 0..200 {
            let (nx, ny) = (1 + rng.below(90), 1 + rng.below(90));
            let density = [0.0, 0.002, 0.02, 0.3, 1.0][case % 5];
            let inside: Vec<bool> = (0..nx * ny).map(|_| rng.next_f64() < density).collect();
            let spacing: f64 = 0.37;
            // Caps on node distances, between them, none and beyond the grid.
            let cap = [0.0, spacing, 2.0 * spacing, 3.3 * spacing, 4.0 * spacing.hypot(spacing), rng.range(0.0, 40.0), 1e9][case % 7];
            let (all, capped) = (distance_to(&inside, nx, ny, spacing), distance_within(&inside, nx, ny, spacing, cap));
            for c in 0..nx * ny {
                let want = if all[c] <= cap { all[c] } else { f64::INFINITY };
                assert_eq!(capped[c].to_bits(), want.to_bits(), "case {case} ({nx} × {ny}, cap {cap}), node {c}");
            }
        }
    }

    #[test]
    fn the_envelope_passes_over_far_values_and_keeps_the_lowest_bit_for_bit() {
        let mut rng = crate::offset::check::Rng::new(61);
        for case in 0..300 {
            let n = 1 + rng.below(120);
            // Whole squared distances, some far: sparse to dense, as the column sweeps leave them.
            let dense = rng.range(0.0, 1.0);
            let f: Vec<f64> = (0..n).map(|_| if rng.range(0.0, 1.0) < dense { rng.below(400) as f64 } else { FAR }).collect();
            let mut work = Envelope::default();
            work.run(&f);
            for q in 0..n {
                let lowest = (0..n).filter(|&p| f[p] < FAR).map(|p| (q as f64 - p as f64).powi(2) + f[p]).reduce(f64::min).unwrap_or(FAR);
                assert_eq!(work.out[q].to_bits(), lowest.to_bits(), "case {case}, node {q} of {n}");
            }
        }
    }

    #[test]
    fn rows_asked_for_are_the_whole_grids_rows_bit_for_bit() {
        let mut rng = crate::offset::check::Rng::new(62);
        for case in 0..200 {
            let (nx, ny) = (1 + rng.below(60), 1 + rng.below(60));
            let dense = rng.range(0.0, 0.3);
            let inside: Vec<bool> = (0..nx * ny).map(|_| rng.range(0.0, 1.0) < dense).collect();
            let cap = rng.range(0.0, 12.0);
            let all = distance_within(&inside, nx, ny, 1.0, cap);
            let from = rng.below(ny + 1);
            let to = from + rng.below(ny + 2 - from);
            let some = distance_within_rows(&inside, nx, ny, 1.0, cap, from..to);
            let want = &all[from * nx..to.min(ny) * nx];
            assert_eq!(some.len(), want.len(), "case {case}");
            for (c, (a, b)) in some.iter().zip(want).enumerate() {
                assert_eq!(a.to_bits(), b.to_bits(), "case {case} ({nx} × {ny}, rows {from}..{to}), node {c}");
            }
        }
    }

    #[test]
    fn nodes_near_a_few_are_those_within_the_cap_of_the_distances() {
        let mut rng = crate::offset::check::Rng::new(71);
        for case in 0..300 {
            let (nx, ny) = (1 + rng.below(70), 1 + rng.below(70));
            let density = [0.0, 0.001, 0.01, 0.1, 0.5][case % 5];
            let mut inside: Vec<bool> = (0..nx * ny).map(|_| rng.next_f64() < density).collect();
            // Nodes on the grid's edges and corners too.
            if case % 3 == 0 {
                for c in [0, nx - 1, nx * ny - 1, (ny - 1) * nx] {
                    inside[c] = true;
                }
            }
            let spacing: f64 = [0.37, 0.19438364128701777, 1.0][case % 3];
            // Caps on node distances (a whole number of nodes, √2, √5, the diagonal), between them, none and beyond the grid.
            let cap = [0.0, spacing, 2.0 * spacing, spacing * 2f64.sqrt(), spacing * 5f64.sqrt(), 1.5 + spacing, rng.range(0.0, 12.0), 1e9][case % 8];
            let marked: Vec<usize> = (0..nx * ny).filter(|&c| inside[c]).collect();
            let (near, d) = (near_any(&marked, nx, ny, spacing, cap), distance_within(&inside, nx, ny, spacing, cap));
            for c in 0..nx * ny {
                assert_eq!(near[c], d[c] <= cap, "case {case} ({nx} × {ny}, cap {cap}), node {c}: {}", d[c]);
            }
        }
    }

    #[test]
    fn distances_match_brute_force() {
        let (nx, ny) = (23, 17);
        let inside: Vec<bool> = (0..nx * ny).map(|c| (c * 7919) % 53 == 0).collect();
        let d = distance_to(&inside, nx, ny, 0.5);
        for c in 0..nx * ny {
            let (i, j) = ((c % nx) as f64, (c / nx) as f64);
            let brute = (0..nx * ny).filter(|&o| inside[o]).map(|o| (((o % nx) as f64 - i).powi(2) + ((o / nx) as f64 - j).powi(2)).sqrt() * 0.5).fold(f64::INFINITY, f64::min);
            assert!((d[c] - brute).abs() < 1e-9, "node {c}: {} against {brute}", d[c]);
        }
    }
}

//! The z-map (dexel) stock of seed 002, and its enhanced form (§3.2, after Lee and Ko).
//!
//! The stock's XY rectangle is cut into square cells; each cell holds the height of the material
//! over its centre (the conventional z-map). A move lowers a cell to the sweep's envelope at
//! that centre, and the volume removed is the drop times the cell's area (clipped to the stock).
//! Its error comes from the cells the footprint's rim crosses: a cell counts as wholly cut or
//! wholly uncut by its centre (Fig. 2 of the paper).
//!
//! The enhanced z-map supersamples exactly those cells: when the rim of a sweep passes through a
//! cell it is split into `k × k` sub-cells, each with its own height at its own centre, and stays
//! split. The rest of the stock keeps one height per cell, so memory grows only along the cut's
//! walls. A cell split after earlier moves cut it starts with its centre's height in every
//! sub-cell (the earlier cuts' detail inside it is not known any more), so the enhanced z-map
//! slightly underestimates what those earlier moves removed there.

use super::sweep::Sweep;
use super::StockModel;
use crate::geom::segment::{Rect, Segment};
use crate::geom::{Aabb, DVec2};
use crate::zmap::{Grid, HeightField};

const UNSPLIT: u32 = u32::MAX;
/// Side of the blocks whose highest cell is kept, so a move skips whole blocks its cutter cannot
/// reach down to (mm). Blocks help when cells are small against the cutter; on cells coarser
/// than this the stock has none.
const BLOCK_SIDE: f64 = 0.5;

/// A column's one span of material (`(floor, top)`, none where the top is not above the
/// floor) as the spans [`DexelStock::with_spans`] takes.
pub fn one_span(material: impl Fn(DVec2) -> (f64, f64)) -> impl FnMut(DVec2, &mut Vec<(f64, f64)>) {
    move |p, spans| {
        let (floor, top) = material(p);
        if top > floor {
            spans.push((floor, top));
        }
    }
}

/// A z-map stock, optionally supersampled where sweeps' rims cross it.
#[derive(Clone, Debug)]
pub struct DexelStock {
    origin: DVec2,
    cell: f64,
    nx: usize,
    ny: usize,
    bottom: f64,
    /// Height over each cell's centre; for a split cell, the highest of its sub-cells.
    z: Vec<f64>,
    /// Cell widths clipped to the stock.
    widths: Vec<f64>,
    heights: Vec<f64>,
    /// Sub-cells per side (1: the conventional z-map).
    k: usize,
    /// Per cell, the index of its `k * k` sub-cell heights in `subs`, or `UNSPLIT`.
    split: Vec<u32>,
    subs: Vec<f64>,
    /// Per cell, the height its material starts at, where that is not the bottom: a stock
    /// turned over, whose columns a setup before cut from what is now below (empty: the bottom
    /// everywhere). A cut down to a cell's floor empties it. Conventional z-maps only.
    floors: Vec<f64>,
    /// Per cell that has them, the spans of material under its top one (`floor` to `z`), lowest
    /// first, with air between: a stock stood on its side, where a column crosses a pocket the
    /// setup before cut from what is now a side. A cut through a cell's top span down into
    /// the air under it leaves the next span down as the cell's top one. Sorted by cell;
    /// conventional z-maps only.
    lower: Vec<(usize, Vec<(f64, f64)>)>,
    /// The highest cell of each block of `BLOCK × BLOCK` cells, row-major.
    block_top: Vec<f64>,
    /// Cells per block side (1: no blocks), and blocks per row.
    block: usize,
    bx: usize,
    /// The horizontal distance from a sweep's path to the nearest cell centre it has cut
    /// deeper than [`ENGAGED`] since [`DexelStock::take_nearest`] (∞ for none): how far the
    /// cut reaches in from the tool's rim, which the chip's thickness follows
    /// ([`crate::sim::feeds`]).
    nearest: f64,
}

/// How deep a cell must be lowered to count as cut by a move's flutes rather than grazed
/// (mm): a pass rerun at the depth of the one before lowers the cells under its centre by
/// rounding alone, and that is no chip.
pub const ENGAGED: f64 = 1e-3;

impl DexelStock {
    /// A box stock on cells of side `cell`, from the box's minimum corner; `k` sub-cells per side
    /// where rims cross (1 for the conventional z-map).
    pub fn new(stock: &Aabb, cell: f64, k: usize) -> DexelStock {
        let size = stock.size().truncate();
        let nx = ((size.x / cell).ceil() as usize).max(1);
        let ny = ((size.y / cell).ceil() as usize).max(1);
        let block = ((BLOCK_SIDE / cell).round() as usize).clamp(1, 16);
        let clipped = |n: usize, extent: f64| (0..n).map(|i| (extent - i as f64 * cell).min(cell)).collect::<Vec<_>>();
        DexelStock {
            origin: stock.min.truncate(),
            cell,
            nx,
            ny,
            bottom: stock.min.z,
            z: vec![stock.max.z; nx * ny],
            widths: clipped(nx, size.x),
            heights: clipped(ny, size.y),
            k: k.max(1),
            split: if k > 1 { vec![UNSPLIT; nx * ny] } else { Vec::new() },
            subs: Vec::new(),
            floors: Vec::new(),
            lower: Vec::new(),
            block_top: vec![stock.max.z; nx.div_ceil(block) * ny.div_ceil(block)],
            block,
            bx: nx.div_ceil(block),
            nearest: f64::INFINITY,
        }
    }

    /// The stock cut into about `count` bands of whole rows of blocks, from the lowest rows up
    /// (one band for a supersampled stock): each band is a stock of its own that moves cut
    /// exactly as they would cut those rows of the whole, so bands can be cut side by side and
    /// [`DexelStock::join`]ed.
    pub fn split_rows(self, count: usize) -> Vec<DexelStock> {
        if self.k > 1 || count <= 1 {
            return vec![self];
        }
        let rows = self.ny.div_ceil(count).div_ceil(self.block).max(1) * self.block;
        let mut out = Vec::new();
        let mut j0 = 0;
        while j0 < self.ny {
            let j1 = (j0 + rows).min(self.ny);
            let (b0, b1) = (j0 / self.block, j1.div_ceil(self.block));
            out.push(DexelStock {
                origin: self.origin + DVec2::new(0.0, j0 as f64 * self.cell),
                ny: j1 - j0,
                z: self.z[j0 * self.nx..j1 * self.nx].to_vec(),
                widths: self.widths.clone(),
                heights: self.heights[j0..j1].to_vec(),
                split: Vec::new(),
                subs: Vec::new(),
                floors: if self.floors.is_empty() { Vec::new() } else { self.floors[j0 * self.nx..j1 * self.nx].to_vec() },
                lower: self.lower.iter().filter(|(c, _)| (j0 * self.nx..j1 * self.nx).contains(c)).map(|(c, spans)| (c - j0 * self.nx, spans.clone())).collect(),
                block_top: self.block_top[b0 * self.bx..b1 * self.bx].to_vec(),
                ..self.clone_shape()
            });
            j0 = j1;
        }
        out
    }

    /// The stock on cells `factor` times as wide, from the same corner, each as high as the
    /// highest of the cells it holds (a split cell by its highest sub-cell): a conventional
    /// z-map that stands nowhere lower than this one, for estimates that may err high, never low.
    pub fn coarsened(&self, factor: usize) -> DexelStock {
        let f = factor.max(1);
        if f == 1 && self.k == 1 {
            return self.clone();
        }
        let (_, max) = self.extent();
        let bounds = Aabb { min: self.origin.extend(self.bottom), max: max.extend(self.bottom) };
        let mut out = DexelStock::new(&bounds, self.cell * f as f64, 1);
        for j in 0..self.ny {
            for i in 0..self.nx {
                let c = (j / f).min(out.ny - 1) * out.nx + (i / f).min(out.nx - 1);
                out.z[c] = out.z[c].max(self.z[j * self.nx + i]);
            }
        }
        for k in 0..out.block_top.len() {
            out.block_top[k] = out.block_highest(k % out.bx, k / out.bx);
        }
        out
    }

    /// The stock with each cell's material `(floor, top)` as `material` gives it at its centre
    /// within this stock's box (an empty column: a top at or below its floor): the stock as
    /// earlier work left it (a bar, a casting). Before any cut; a conventional z-map's cells
    /// only.
    pub fn with_material(self, material: impl Fn(DVec2) -> (f64, f64)) -> DexelStock {
        self.with_spans(one_span(material))
    }

    /// The stock with each cell's material the spans `(floor, top)` that `material` pushes for
    /// its centre, lowest first, air between them (clipped to this stock's box; spans that
    /// touch are one): the stock as the setup before left it, turned into this one's frame.
    /// Before any cut; a conventional z-map's cells only.
    pub fn with_spans(mut self, mut material: impl FnMut(DVec2, &mut Vec<(f64, f64)>)) -> DexelStock {
        debug_assert!(self.k == 1, "a conventional z-map");
        let g = self.grid();
        let top = self.z.first().copied().unwrap_or(self.bottom);
        let mut floors = vec![self.bottom; self.z.len()];
        let mut lower = Vec::new();
        let mut spans = Vec::new();
        for j in 0..self.ny {
            for i in 0..self.nx {
                let c = j * self.nx + i;
                spans.clear();
                material(g.origin + DVec2::new(i as f64, j as f64) * g.spacing, &mut spans);
                let mut kept: Vec<(f64, f64)> = Vec::with_capacity(spans.len());
                for &(f, t) in spans.iter() {
                    let (f, t) = (f.max(self.bottom), t.min(top));
                    if t <= f {
                        continue;
                    }
                    match kept.last_mut() {
                        Some(last) if f <= last.1 => last.1 = last.1.max(t),
                        _ => kept.push((f, t)),
                    }
                }
                (self.z[c], floors[c]) = match kept.pop() {
                    Some((f, t)) => (t, f),
                    None => (self.bottom, self.bottom),
                };
                if !kept.is_empty() {
                    lower.push((c, kept));
                }
            }
        }
        self.floors = if floors.iter().any(|&f| f > self.bottom) { floors } else { Vec::new() };
        self.lower = lower;
        for k in 0..self.block_top.len() {
            self.block_top[k] = self.block_highest(k % self.bx, k / self.bx);
        }
        self
    }

    /// The spans of material of cell (i, j), lowest first: those under its top one, then its
    /// top one (none where the column is empty).
    pub fn spans(&self, i: usize, j: usize) -> impl Iterator<Item = (f64, f64)> + '_ {
        let c = j * self.nx + i;
        let under = self.lower.binary_search_by_key(&c, |e| e.0).map_or(&[][..], |k| &self.lower[k].1[..]);
        let (floor, top) = (self.floor(i, j), self.z[c]);
        under.iter().copied().chain((top > floor && top > self.bottom).then_some((floor, top)))
    }

    /// Along which axes (x, y) the cells are laid from the box's maximum side, the first
    /// cell the one clipped to the box ([`DexelStock::laid_from`]); a box a whole number of
    /// cells wide is laid alike from either side.
    pub fn laid_from_max(&self) -> [bool; 2] {
        let first_clipped = |w: &[f64]| w.len() > 1 && w[0] < w[w.len() - 1];
        [first_clipped(&self.widths), first_clipped(&self.heights)]
    }

    /// The box this stock covers, seen from above.
    fn extent(&self) -> (DVec2, DVec2) {
        let [mx, my] = self.laid_from_max();
        let n = DVec2::new(self.nx as f64, self.ny as f64) * self.cell;
        let size = DVec2::new(self.widths.iter().sum(), self.heights.iter().sum());
        let min = self.origin + DVec2::new(if mx { n.x - size.x } else { 0.0 }, if my { n.y - size.y } else { 0.0 });
        (min, min + size)
    }

    /// The same fresh box stock with its cells laid from the box's maximum side along the axes
    /// `at_max` marks (x, y), its first cell there the one clipped: the stock of a setup turned
    /// over from one laid the other way, whose cells' centres are then the very images of the
    /// cells' centres of the setup before, so that what that setup left carries over cell for
    /// cell ([`crate::job::setups::carried`]), never half a cell off at a hole's rim.
    pub fn laid_from(self, at_max: [bool; 2]) -> DexelStock {
        if at_max == self.laid_from_max() {
            return self;
        }
        let (min, max) = self.extent();
        let box3 = Aabb { min: min.extend(self.bottom), max: max.extend(self.z.first().copied().unwrap_or(self.bottom)) };
        let mut out = DexelStock::new(&box3, self.cell, self.k);
        if at_max[0] {
            out.origin.x = max.x - out.nx as f64 * out.cell;
            out.widths.reverse();
        }
        if at_max[1] {
            out.origin.y = max.y - out.ny as f64 * out.cell;
            out.heights.reverse();
        }
        out
    }

    /// Where the material of cell (i, j) starts: its floor, or the bottom.
    pub fn floor(&self, i: usize, j: usize) -> f64 {
        self.floors.get(j * self.nx + i).copied().unwrap_or(self.bottom)
    }

    /// The highest cell of block (`bi`, `bj`) (the stock's bottom where none stands higher).
    fn block_highest(&self, bi: usize, bj: usize) -> f64 {
        let size = self.block;
        let (ci, ce) = (bi * size, ((bi + 1) * size).min(self.nx));
        (bj * size..((bj + 1) * size).min(self.ny)).fold(self.bottom, |highest, j| self.z[j * self.nx + ci..j * self.nx + ce].iter().fold(highest, |m, &z| m.max(z)))
    }

    /// The bands of [`DexelStock::split_rows`] as one stock again.
    pub fn join(bands: Vec<DexelStock>) -> DexelStock {
        let mut bands = bands.into_iter();
        let mut whole = bands.next().expect("a stock has at least one band");
        for band in bands {
            let offset = whole.z.len();
            whole.ny += band.ny;
            whole.z.extend(band.z);
            whole.heights.extend(band.heights);
            whole.block_top.extend(band.block_top);
            whole.floors.extend(band.floors);
            whole.lower.extend(band.lower.into_iter().map(|(c, spans)| (c + offset, spans)));
        }
        whole
    }

    /// Writes the stock (a conventional one: a band of [`DexelStock::split_rows`]) to `out` as
    /// flat numbers, for a worker of the page's pool; [`DexelStock::all_from_flat`] reads them.
    pub fn to_flat(&self, out: &mut Vec<f64>) {
        debug_assert_eq!(self.k, 1, "only a conventional z-map is cut in bands");
        // The spans under cells' top ones: the cell, how many, then each span's floor and top.
        let lower: Vec<f64> = self.lower.iter().flat_map(|(c, spans)| [*c as f64, spans.len() as f64].into_iter().chain(spans.iter().flat_map(|&(f, t)| [f, t]))).collect();
        out.extend([
            self.nx as f64,
            self.ny as f64,
            self.origin.x,
            self.origin.y,
            self.cell,
            self.bottom,
            self.block as f64,
            self.bx as f64,
            self.block_top.len() as f64,
            self.floors.len() as f64,
            lower.len() as f64,
        ]);
        out.extend_from_slice(&self.z);
        out.extend_from_slice(&self.widths);
        out.extend_from_slice(&self.heights);
        out.extend_from_slice(&self.block_top);
        out.extend_from_slice(&self.floors);
        out.extend_from_slice(&lower);
    }

    /// `stocks` written by [`DexelStock::to_flat`] one after another.
    pub fn all_to_flat(stocks: &[DexelStock]) -> Vec<f64> {
        let mut out = Vec::new();
        stocks.iter().for_each(|s| s.to_flat(&mut out));
        out
    }

    /// The stocks [`DexelStock::to_flat`] wrote one after another in `flat`.
    pub fn all_from_flat(flat: &[f64]) -> Option<Vec<DexelStock>> {
        let mut out = Vec::new();
        let mut rest = flat;
        while !rest.is_empty() {
            let head = rest.get(..11)?;
            let (nx, ny, blocks, floors, lower) = (head[0] as usize, head[1] as usize, head[8] as usize, head[9] as usize, head[10] as usize);
            let mut at: usize = 11;
            let mut take = |n: usize| -> Option<Vec<f64>> {
                let v = rest.get(at..at.checked_add(n)?)?.to_vec();
                at += n;
                Some(v)
            };
            let (z, widths, heights, block_top, floors, flat_lower) = (take(nx.checked_mul(ny)?)?, take(nx)?, take(ny)?, take(blocks)?, take(floors)?, take(lower)?);
            let mut lower = Vec::new();
            let mut k = 0;
            while k < flat_lower.len() {
                let (c, n) = (*flat_lower.get(k)? as usize, *flat_lower.get(k + 1)? as usize);
                let spans = flat_lower.get(k + 2..k + 2 + 2 * n)?.chunks(2).map(|p| (p[0], p[1])).collect();
                lower.push((c, spans));
                k += 2 + 2 * n;
            }
            out.push(DexelStock {
                origin: DVec2::new(head[2], head[3]),
                cell: head[4],
                nx,
                ny,
                bottom: head[5],
                z,
                widths,
                heights,
                k: 1,
                split: Vec::new(),
                subs: Vec::new(),
                floors,
                lower,
                block_top,
                block: head[6] as usize,
                bx: head[7] as usize,
                nearest: f64::INFINITY,
            });
            rest = &rest[at..];
        }
        Some(out)
    }

    /// The y range of the stock's rows (its band of the whole, after [`DexelStock::split_rows`]).
    pub fn rows(&self) -> (f64, f64) {
        (self.origin.y, self.origin.y + self.ny as f64 * self.cell)
    }

    /// The stock, leaving in its place one with its settings and no cells.
    pub fn take(&mut self) -> DexelStock {
        let empty = self.clone_shape();
        std::mem::replace(self, empty)
    }

    /// The stock's settings with no cells (for [`DexelStock::split_rows`]).
    fn clone_shape(&self) -> DexelStock {
        DexelStock { z: Vec::new(), widths: Vec::new(), heights: Vec::new(), split: Vec::new(), subs: Vec::new(), floors: Vec::new(), lower: Vec::new(), block_top: Vec::new(), ..*self }
    }

    #[inline]
    fn is_split(&self, c: usize) -> Option<usize> {
        match self.split.get(c) {
            Some(&s) if s != UNSPLIT => Some(s as usize),
            _ => None,
        }
    }

    /// Where the cells' centres stand.
    pub fn grid(&self) -> Grid {
        Grid { origin: self.origin + DVec2::splat(self.cell * 0.5), spacing: self.cell, nx: self.nx, ny: self.ny }
    }

    pub fn cells(&self) -> usize {
        self.nx * self.ny
    }

    /// Cells split into sub-cells so far.
    pub fn split_cells(&self) -> usize {
        self.subs.len() / (self.k * self.k)
    }

    /// The material's height over each cell's centre (a split cell: the mean of its sub-cells).
    pub fn heights(&self) -> HeightField {
        let k2 = self.k * self.k;
        let z = (0..self.cells())
            .map(|c| match self.is_split(c) {
                None => self.z[c],
                Some(s) => self.subs[s * k2..(s + 1) * k2].iter().sum::<f64>() / k2 as f64,
            })
            .collect();
        let g = self.grid();
        HeightField { origin: g.origin, spacing: g.spacing, nx: g.nx, ny: g.ny, z }
    }

    /// The height over cell (i, j)'s centre, as the conventional z-map samples it.
    pub fn top(&self, i: usize, j: usize) -> f64 {
        self.z[j * self.nx + i]
    }

    /// [`DexelStock::top`] of every cell, by rows.
    pub fn tops(&self) -> &[f64] {
        &self.z
    }

    /// [`DexelStock::top`] of the cell whose centre is nearest `p`; `None` off the stock.
    pub fn top_near(&self, p: DVec2) -> Option<f64> {
        self.grid().nearest(p).map(|c| self.z[c])
    }

    /// Whether material stands above `z` anywhere over the rectangle from `lo` to `hi`: in a
    /// cell whose square meets it (a cell's material lies at its centre, a split cell's at its
    /// sub-cells' anywhere in its square; its top is their highest).
    pub fn material_over(&self, lo: DVec2, hi: DVec2, z: f64) -> bool {
        let Some(((i0, i1), (j0, j1))) = self.cell_range(lo, hi) else { return false };
        (j0..=j1).any(|j| self.z[j * self.nx + i0..=j * self.nx + i1].iter().any(|&top| top > z + crate::geom::tolerance::MATERIAL_SLACK))
    }

    /// The worst place where material stands more than `rise` above the tip within `radius` of
    /// the sweep's path (the tool's body above its flutes would meet it): the point and by how
    /// much, or `None`. A cell counts when its centre lies at least half a cell inside that
    /// footprint: a cell's column stands for its centre, and a path that passes a hair closer
    /// to a wall's leave-stock at one level than at the one above would otherwise read as the
    /// body burying itself in the whole column beside its flutes.
    pub fn above_body(&self, sweep: &Sweep, radius: f64, rise: f64) -> Option<(DVec2, f64)> {
        let grow = DVec2::splat(radius - sweep.profile.radius);
        let ((i0, i1), (j0, j1)) = self.cell_range(sweep.min - grow, sweep.max + grow)?;
        let mut worst: Option<(DVec2, f64)> = None;
        let low = sweep.lowest_tip + rise;
        let size = self.block;
        for bj in j0 / size..=j1 / size {
            for bi in i0 / size..=i1 / size {
                // A block no higher than the body's lowest point has nothing to meet.
                if size > 1 && self.block_top[bj * self.bx + bi] <= low {
                    continue;
                }
                let (ce, cje) = (((bi + 1) * size).min(self.nx).min(i1 + 1), ((bj + 1) * size).min(self.ny).min(j1 + 1));
                for j in (bj * size).max(j0)..cje {
                    for i in (bi * size).max(i0)..ce {
                        self.body_meets(sweep, radius, rise, i, j, &mut worst);
                    }
                }
            }
        }
        worst
    }

    /// [`DexelStock::above_body`] at cell (i, j): kept in `worst` where it is worse.
    #[inline]
    fn body_meets(&self, sweep: &Sweep, radius: f64, rise: f64, i: usize, j: usize, worst: &mut Option<(DVec2, f64)>) {
        let top = self.z[j * self.nx + i];
        if top <= sweep.lowest_tip + rise {
            return;
        }
        let centre = self.origin + (DVec2::new(i as f64, j as f64) + 0.5) * self.cell;
        let (dist, z) = sweep.nearest(centre);
        let excess = top - (z + rise);
        if dist <= radius - 0.5 * self.cell && excess > 0.0 && worst.is_none_or(|w| excess > w.1) {
            *worst = Some((centre, excess));
        }
    }

    /// The highest tip height at which a cutter of `profile` standing at `c` touches the
    /// material, `-inf` where no material is within reach. `whole_cells`: each cell's material
    /// is taken as a column over its whole square, so the answer is never lower than the
    /// material's (for rapids); otherwise as the z-map samples it, at the cells' centres (an
    /// estimate, for deciding what is left to cut). Blocks no higher than the best answer so
    /// far are skipped.
    pub fn touch(&self, c: DVec2, profile: &crate::cutter::Profile, whole_cells: bool) -> f64 {
        self.touch_along(c, c, profile, whole_cells)
    }

    /// [`DexelStock::touch`] anywhere along the straight way from `a` to `b`: the lowest height
    /// at which the cutter can travel level from above `a` to above `b` without touching the
    /// material (a column's distance from the way is its square's, or its centre's).
    pub fn touch_along(&self, a: DVec2, b: DVec2, profile: &crate::cutter::Profile, whole_cells: bool) -> f64 {
        self.touch_from(a, b, profile, whole_cells, f64::NEG_INFINITY, false)
    }

    /// Whether [`DexelStock::touch_along`] stands above `h`, looked up only in the cells
    /// higher than `h` and as far as the first that decides: where the material mostly stands
    /// lower (a place to go down in the air beside a pass), most blocks are passed over.
    pub fn touches_above(&self, a: DVec2, b: DVec2, profile: &crate::cutter::Profile, whole_cells: bool, h: f64) -> bool {
        self.touch_from(a, b, profile, whole_cells, h, true) > h
    }

    /// The highest of `from` and [`DexelStock::touch_along`]'s heights, or with `first` the
    /// first of those found above `from` (the cutter's lower surface stands no lower than its
    /// tip, so no cell lower than that height can rise above it).
    fn touch_from(&self, a: DVec2, b: DVec2, profile: &crate::cutter::Profile, whole_cells: bool, from: f64, first: bool) -> f64 {
        let r = profile.radius;
        let reach = DVec2::splat(r + self.cell);
        let half_diagonal = self.cell * std::f64::consts::FRAC_1_SQRT_2;
        let way = Segment::line(a, b);
        let Some(((i0, i1), (j0, j1))) = self.cell_range(a.min(b) - reach, a.max(b) + reach) else { return from };
        let mut best = from;
        let size = self.block;
        for bj in j0 / size..=j1 / size {
            for bi in i0 / size..=i1 / size {
                if size > 1 && self.block_top[bj * self.bx + bi] <= best.max(self.bottom) {
                    continue;
                }
                let (ce, cje) = (((bi + 1) * size).min(self.nx).min(i1 + 1), ((bj + 1) * size).min(self.ny).min(j1 + 1));
                for j in (bj * size).max(j0)..cje {
                    for i in (bi * size).max(i0)..ce {
                        let top = self.z[j * self.nx + i];
                        if top <= self.bottom || top <= best {
                            continue;
                        }
                        let lo = self.origin + DVec2::new(i as f64, j as f64) * self.cell;
                        let (square, centre) = (Rect { min: lo, max: lo + DVec2::splat(self.cell) }, lo + DVec2::splat(self.cell * 0.5));
                        let d = if !whole_cells {
                            way.distance_with(None, centre)
                        } else if a == b || way.distance_with(None, centre) <= r + half_diagonal {
                            square_distance(&way, &square)
                        } else {
                            continue; // a square is no nearer than its centre less half its diagonal
                        };
                        if d <= r {
                            best = best.max(top - profile.height(d));
                            if first && best > from {
                                return best;
                            }
                        }
                    }
                }
            }
        }
        best
    }

    /// The cells whose centres the rectangle `[lo, hi]` may touch, or `None`.
    fn cell_range(&self, lo: DVec2, hi: DVec2) -> Option<((usize, usize), (usize, usize))> {
        let a = ((lo - self.origin) / self.cell).floor();
        let b = ((hi - self.origin) / self.cell).floor();
        if b.x < 0.0 || b.y < 0.0 || a.x >= self.nx as f64 || a.y >= self.ny as f64 {
            return None;
        }
        let clamp = |v: f64, n: usize| v.clamp(0.0, n as f64 - 1.0) as usize;
        Some(((clamp(a.x, self.nx), clamp(b.x, self.nx)), (clamp(a.y, self.ny), clamp(b.y, self.ny))))
    }
}

impl DexelStock {
    /// Cuts cell (i, j); returns the volume removed. Most cells a sweep's footprint covers
    /// stand below its tip, and a conventional z-map's cell is one point: both are decided
    /// here, inline in the loops over the footprint; a supersampled cell goes to
    /// [`DexelStock::cut_split_cell`].
    #[inline(always)]
    fn cut_cell(&mut self, sweep: &Sweep, i: usize, j: usize, reach: f64) -> f64 {
        let c = j * self.nx + i;
        let top = self.z[c];
        if top <= sweep.lowest_tip || top <= self.bottom {
            return 0.0; // the cutter never reaches down to this cell's material
        }
        if self.k > 1 {
            return self.cut_split_cell(sweep, i, j, reach);
        }
        self.cut_whole_cell(sweep, i, j, top, self.origin + (DVec2::new(i as f64, j as f64) + 0.5) * self.cell)
    }

    /// Lowers the whole of cell (i, j), its material at `top`, to the sweep's envelope over its
    /// `centre`; returns the volume removed.
    #[inline(always)]
    fn cut_whole_cell(&mut self, sweep: &Sweep, i: usize, j: usize, top: f64, centre: DVec2) -> f64 {
        let e = sweep.lowest(centre);
        if e < top {
            let c = j * self.nx + i;
            let floor = self.floors.get(c).copied().unwrap_or(self.bottom);
            if e > floor {
                self.z[c] = e;
                self.engaged(sweep, centre, top - e);
                return (top - e) * self.widths[i] * self.heights[j];
            }
            // Cut down to its floor, the top span is gone: the next one down, if any, is the
            // top one now; with none, nothing stands in the column any more.
            self.z[c] = self.bottom;
            self.engaged(sweep, centre, top - e);
            let removed = top - floor + if self.lower.is_empty() { 0.0 } else { self.cut_lower(c, e) };
            return removed * self.widths[i] * self.heights[j];
        }
        0.0
    }

    /// Notes a cell at `centre` cut `depth` deep by `sweep` in [`DexelStock::nearest`].
    #[inline(always)]
    fn engaged(&mut self, sweep: &Sweep, centre: DVec2, depth: f64) {
        // (A cell no nearer than the nearest so far, by a cheaper bound, changes nothing.)
        if depth > ENGAGED && sweep.nearest_at_least(centre) < self.nearest {
            self.nearest = self.nearest.min(sweep.nearest(centre).0);
        }
    }

    /// The nearest any sweep since the last call came to a cell it cut (horizontally, from
    /// its tip's path to the cell's centre; ∞ for none), and starts afresh.
    pub fn take_nearest(&mut self) -> f64 {
        std::mem::replace(&mut self.nearest, f64::INFINITY)
    }

    /// Cell `c`'s top span cut away: its spans under it cut down to `e`, the highest left the
    /// top one ([`DexelStock::lower`]); returns the height of material removed.
    #[inline(never)]
    fn cut_lower(&mut self, c: usize, e: f64) -> f64 {
        let Ok(k) = self.lower.binary_search_by_key(&c, |x| x.0) else { return 0.0 };
        let mut removed = 0.0;
        let spans = &mut self.lower[k].1;
        while let Some((f, t)) = spans.pop() {
            removed += (t - e.max(f)).max(0.0);
            if e > f {
                (self.z[c], self.floors[c]) = (e.min(t), f);
                break;
            }
        }
        if spans.is_empty() {
            self.lower.remove(k);
        }
        removed
    }

    /// [`DexelStock::cut_cell`] on a supersampled stock, for a cell whose material the sweep
    /// may reach.
    #[inline(never)]
    fn cut_split_cell(&mut self, sweep: &Sweep, i: usize, j: usize, reach: f64) -> f64 {
        let c = j * self.nx + i;
        let top = self.z[c];
        let centre = self.origin + (DVec2::new(i as f64, j as f64) + 0.5) * self.cell;
        let area = self.widths[i] * self.heights[j];
        let (k, k2) = (self.k, self.k * self.k);
        let base = match self.is_split(c) {
            Some(s) => s * k2,
            None => {
                if !sweep.rim_near(centre, reach) {
                    return self.cut_whole_cell(sweep, i, j, top, centre);
                }
                let s = self.subs.len() / k2;
                self.split[c] = s as u32;
                self.subs.extend(std::iter::repeat_n(top, k2));
                s * k2
            }
        };
        let sub = self.cell / k as f64;
        let corner = centre - DVec2::splat(self.cell * 0.5);
        let (mut removed, mut highest) = (0.0, self.bottom);
        for b in 0..k {
            for a in 0..k {
                let h = &mut self.subs[base + b * k + a];
                if *h > sweep.lowest_tip {
                    let e = sweep.lowest(corner + DVec2::new((a as f64 + 0.5) * sub, (b as f64 + 0.5) * sub));
                    if e < *h {
                        let new = e.max(self.bottom);
                        removed += (*h - new) * area / k2 as f64;
                        *h = new;
                    }
                }
                highest = highest.max(*h);
            }
        }
        self.z[c] = highest;
        removed
    }
}

impl StockModel for DexelStock {
    fn apply(&mut self, sweep: &Sweep) -> f64 {
        let Some(((i0, i1), (j0, j1))) = self.cell_range(sweep.min, sweep.max) else { return 0.0 };
        let reach = self.cell * std::f64::consts::FRAC_1_SQRT_2;
        let mut removed = 0.0;
        let size = self.block;
        if size == 1 {
            for j in j0..=j1 {
                for i in i0..=i1 {
                    removed += self.cut_cell(sweep, i, j, reach);
                }
            }
            return removed;
        }
        for bj in j0 / size..=j1 / size {
            for bi in i0 / size..=i1 / size {
                let block = bj * self.bx + bi;
                let (ci, cj) = (bi * size, bj * size);
                let (ce, cje) = ((ci + size).min(self.nx), (cj + size).min(self.ny));
                let lo = self.origin + DVec2::new(ci as f64, cj as f64) * self.cell;
                let hi = self.origin + DVec2::new(ce as f64, cje as f64) * self.cell;
                if self.block_top[block] <= sweep.bounds_over(lo, hi).0 {
                    continue;
                }
                let before = removed;
                for j in cj.max(j0)..cje.min(j1 + 1) {
                    for i in ci.max(i0)..ce.min(i1 + 1) {
                        removed += self.cut_cell(sweep, i, j, reach);
                    }
                }
                if removed > before {
                    self.block_top[block] = self.block_highest(bi, bj);
                }
            }
        }
        removed
    }

    fn volume(&self) -> f64 {
        let k2 = self.k * self.k;
        let mut total = 0.0;
        for j in 0..self.ny {
            for i in 0..self.nx {
                let c = j * self.nx + i;
                let mean_height = match self.is_split(c) {
                    None => self.spans(i, j).map(|(f, t)| t - f).sum(),
                    Some(s) => self.subs[s * k2..(s + 1) * k2].iter().map(|h| h - self.bottom).sum::<f64>() / k2 as f64,
                };
                total += mean_height * self.widths[i] * self.heights[j];
            }
        }
        total
    }
}

/// The distance from the straight `way` to the `square` (0 where they meet): the nearer of its
/// ends' distances to the square and the square's corners' to it.
fn square_distance(way: &Segment, square: &Rect) -> f64 {
    let to_square = |p: DVec2| p.clamp(square.min, square.max).distance(p);
    if way.a == way.b {
        return to_square(way.a);
    }
    if square.clip(way.a, way.b).is_some() {
        return 0.0;
    }
    let (lo, hi) = (square.min, square.max);
    let corners = [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
    corners.iter().map(|&c| way.distance_with(None, c)).fold(to_square(way.a).min(to_square(way.b)), f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cutter::Profile;
    use crate::geom::DVec3;

    #[test]
    fn a_coarsened_stock_stands_nowhere_lower() {
        let fine = randomly_cut(uniform(7), 40, Profile::new(1.5, 0.5));
        let mut next = uniform(8);
        let coarse = fine.coarsened(4);
        assert_eq!((coarse.nx, coarse.ny), (fine.nx.div_ceil(4), fine.ny.div_ceil(4)));
        let g = coarse.grid();
        for j in 0..fine.ny {
            for i in 0..fine.nx {
                let (ci, cj) = (i / 4, j / 4);
                assert!(coarse.top(ci, cj) >= fine.top(i, j), "cell ({i}, {j})");
                // Each coarse cell is the highest of its own cells.
                let own = (0..fine.ny).filter(|&y| y / 4 == cj).flat_map(|y| (0..fine.nx).filter(move |&x| x / 4 == ci).map(move |x| (x, y)));
                assert_eq!(own.map(|(x, y)| fine.top(x, y)).fold(f64::NEG_INFINITY, f64::max), coarse.top(ci, cj));
            }
        }
        // A whole-cells answer on the coarse stock is never below the fine one's.
        for _ in 0..200 {
            let c = g.origin + DVec2::new(20.0 * next(), 15.0 * next());
            let p = Profile::new(2.0, 0.0);
            assert!(coarse.touch(c, &p, true) >= fine.touch(c, &p, true));
        }
    }

    /// A 20.3 × 15.1 × 10 mm stock of 0.1 mm cells cut by `sweeps` straight sweeps of
    /// `profile` between points `next` places.
    fn randomly_cut(mut next: impl FnMut() -> f64, sweeps: usize, profile: Profile) -> DexelStock {
        let bounds = Aabb { min: DVec3::new(-10.0, -7.0, 0.0), max: DVec3::new(10.3, 8.1, 10.0) };
        let mut stock = DexelStock::new(&bounds, 0.1, 1);
        for _ in 0..sweeps {
            let mut at = || DVec3::new(-10.0 + 20.3 * next(), -7.0 + 15.1 * next(), 10.0 * next());
            stock.apply(&Sweep::line(profile, at(), at()));
        }
        stock
    }

    /// Numbers in [0, 1) from `seed`, the same every run.
    fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Whether the material stands above a height, looked up from that height and stopping at
    /// the first cell above it, says what the highest touch says: on a stock cut by random
    /// sweeps, at points and along ways, for every cutter shape, at heights around the touch.
    #[test]
    fn touches_above_is_the_highest_touch_above_the_height() {
        let stock = randomly_cut(uniform(11), 60, Profile::new(2.0, 1.0));
        let mut next = uniform(12);
        let mut checked = [0, 0];
        for profile in [Profile::new(3.0, 0.0), Profile::new(3.0, 3.0), Profile::new(1.5, 0.5)] {
            for _ in 0..400 {
                let a = DVec2::new(-12.0 + 24.0 * next(), -9.0 + 19.0 * next());
                let b = if next() < 0.5 { a } else { a + DVec2::new(6.0 * next() - 3.0, 6.0 * next() - 3.0) };
                for whole in [true, false] {
                    let touch = stock.touch_along(a, b, &profile, whole);
                    for h in [touch - 0.5, touch - 1e-9, touch, touch + 1e-9, 12.0 * next() - 1.0, f64::NEG_INFINITY] {
                        let above = stock.touches_above(a, b, &profile, whole, h);
                        assert_eq!(above, touch > h, "{a} to {b}, {profile:?}, whole cells {whole}, height {h} against {touch}");
                        checked[usize::from(above)] += 1;
                    }
                }
            }
        }
        assert!(checked[0] > 1000 && checked[1] > 1000, "{checked:?}");
    }

    /// The body test skips a block only where nothing in it stands above the body's lowest
    /// point: on a stock cut into steps and pockets, for sweeps at every depth, it finds the
    /// same worst excess as a scan of every cell.
    #[test]
    fn the_body_test_skips_only_blocks_it_cannot_meet() {
        let mut stock = DexelStock::new(&Aabb { min: DVec3::ZERO, max: DVec3::new(40.0, 30.0, 20.0) }, 0.25, 1);
        assert!(stock.block > 1);
        let flat = Profile::new(3.0, 0.0);
        for (a, b) in [((5.0, 5.0, 12.0), (35.0, 5.0, 12.0)), ((8.0, 8.0, 6.0), (8.0, 25.0, 6.0)), ((20.0, 15.0, 2.0), (30.0, 22.0, 2.0)), ((12.0, 20.0, 15.0), (14.0, 21.0, 15.0))] {
            stock.apply(&Sweep::line(flat, DVec3::from(a), DVec3::from(b)));
        }
        let mut next = uniform(7);
        let (mut met, mut clear) = (0, 0);
        for _ in 0..400 {
            let a = DVec3::new(40.0 * next(), 30.0 * next(), 20.0 * next());
            let b = a + DVec3::new(8.0 * next() - 4.0, 8.0 * next() - 4.0, 0.0);
            let sweep = Sweep::line(flat, a, b);
            let (radius, rise) = (3.0 + 2.0 * next(), 4.0 * next());
            let found = stock.above_body(&sweep, radius, rise).map(|w| w.1);
            let mut worst = None;
            let grow = DVec2::splat(radius - 3.0);
            if let Some(((i0, i1), (j0, j1))) = stock.cell_range(sweep.min - grow, sweep.max + grow) {
                for j in j0..=j1 {
                    for i in i0..=i1 {
                        stock.body_meets(&sweep, radius, rise, i, j, &mut worst);
                    }
                }
            }
            assert_eq!(found, worst.map(|w| w.1), "{a} {b}");
            if found.is_some() {
                met += 1;
            } else {
                clear += 1;
            }
        }
        assert!(met > 40 && clear > 40, "{met} met, {clear} clear");
    }

    /// Bands of rows cut by the same sweeps, each on its own, join into the stock the whole one
    /// becomes, cell for cell, and remove the same volume; the body test finds the same worst
    /// place in one of them. Flat ends, balls and bull noses, level and sloped moves, bands of
    /// uneven height (the stock's rows are no multiple of them).
    #[test]
    fn bands_cut_as_the_whole_stock_does() {
        let whole = DexelStock::new(&Aabb { min: DVec3::ZERO, max: DVec3::new(40.0, 30.1, 20.0) }, 0.25, 1);
        let mut bands = whole.clone().split_rows(7);
        assert!(bands.len() > 3 && bands.iter().all(|b| b.ny % whole.block == 0 || b.origin.y + b.ny as f64 * 0.25 > 30.0), "{}", bands.len());
        let mut whole = whole;
        let mut next = uniform(5);
        for k in 0..300 {
            let profile = [Profile::new(3.0, 0.0), Profile::new(3.0, 3.0), Profile::new(3.0, 1.0)][k % 3];
            let a = DVec3::new(40.0 * next(), 30.0 * next(), 20.0 * next());
            let b = a + DVec3::new(12.0 * next() - 6.0, 12.0 * next() - 6.0, if k % 2 == 0 { 0.0 } else { 4.0 * next() - 2.0 });
            let sweep = Sweep::line(profile, a, b);
            let body = whole.above_body(&sweep, 4.0, 6.0).map(|w| w.1);
            let in_bands = bands.iter().filter_map(|band| band.above_body(&sweep, 4.0, 6.0)).map(|w| w.1).fold(None, |w: Option<f64>, b| Some(w.map_or(b, |w| w.max(b))));
            assert_eq!(body, in_bands, "{a} {b}");
            let removed = whole.apply(&sweep);
            let banded: f64 = bands.iter_mut().map(|band| band.apply(&sweep)).sum();
            assert!((removed - banded).abs() <= 1e-9 * removed.max(1.0), "{removed} against {banded}");
        }
        let joined = DexelStock::join(bands);
        assert_eq!(joined.z, whole.z);
        assert_eq!(joined.block_top, whole.block_top);
        assert_eq!((joined.ny, joined.heights.clone()), (whole.ny, whole.heights.clone()));
        assert!(whole.volume() < 40.0 * 30.1 * 20.0 * 0.9);
    }

    /// The height a level traverse must keep along a way is at least the touch at every point
    /// of it (dense points, each cell's whole square), and no more than a flat end a hair wider
    /// finds at those points: on a stock cut into steps and pockets, for flat ends, balls and
    /// bull noses, long and short ways.
    #[test]
    fn the_touch_along_a_way_is_the_highest_touch_on_it() {
        let mut stock = DexelStock::new(&Aabb { min: DVec3::ZERO, max: DVec3::new(40.0, 30.0, 20.0) }, 0.25, 1);
        let flat = Profile::new(3.0, 0.0);
        // Faced down to 14 but for a strip along y = 30, then steps and pockets.
        for y in (0..7).map(|k| k as f64 * 4.0) {
            stock.apply(&Sweep::line(flat, DVec3::new(-3.0, y, 14.0), DVec3::new(43.0, y, 14.0)));
        }
        for (a, b) in [((5.0, 5.0, 12.0), (35.0, 5.0, 12.0)), ((8.0, 8.0, 6.0), (8.0, 25.0, 6.0)), ((20.0, 15.0, 2.0), (30.0, 22.0, 2.0)), ((12.0, 20.0, 9.0), (14.0, 21.0, 9.0))] {
            stock.apply(&Sweep::line(flat, DVec3::from(a), DVec3::from(b)));
        }
        let mut next = uniform(11);
        let mut below_top = 0;
        for k in 0..300 {
            let profile = [Profile::new(3.0, 0.0), Profile::new(3.0, 3.0), Profile::new(3.0, 1.0)][k % 3];
            let a = DVec2::new(40.0 * next(), 30.0 * next());
            let b = if k % 10 == 0 { a } else { a + DVec2::new(30.0 * next() - 15.0, 30.0 * next() - 15.0) };
            let n = 2000;
            let points = (0..=n).map(|q| a.lerp(b, q as f64 / n as f64));
            let along = stock.touch_along(a, b, &profile, true);
            let highest = points.clone().map(|p| stock.touch(p, &profile, true)).fold(f64::NEG_INFINITY, f64::max);
            assert!(along >= highest - 1e-12, "{a} {b} {profile:?}: {along} below {highest}");
            let wider = Profile::new(3.0 + a.distance(b) / n as f64, 0.0);
            let bound = points.map(|p| stock.touch(p, &wider, true)).fold(f64::NEG_INFINITY, f64::max);
            assert!(along <= bound + 1e-12, "{a} {b} {profile:?}: {along} above {bound}");
            if along < 19.0 {
                below_top += 1;
            }
        }
        assert!(below_top > 30, "{below_top} ways below the stock's top");
    }

    /// A column with a cavity (a stock stood on its side): cut through its top span into the
    /// air under it, the span under that is its top one; volumes add up; bands and the flat
    /// form keep the spans.
    #[test]
    fn a_cut_through_a_top_span_finds_the_span_under_it() {
        use crate::sim::StockModel;
        let raw = Aabb { min: DVec3::new(0.0, 0.0, 0.0), max: DVec3::new(4.0, 4.0, 10.0) };
        // Every column 0–2 and 6–9, air between; one column (1, 1) solid 0–9.
        let stock = DexelStock::new(&raw, 1.0, 1).with_spans(|p, spans| {
            if (p.x - 1.5).abs() < 0.1 && (p.y - 1.5).abs() < 0.1 {
                spans.extend([(0.0, 3.0), (3.0, 9.0)]);
            } else {
                spans.extend([(0.0, 2.0), (6.0, 9.0)]);
            }
        });
        assert!((stock.volume() - (15.0 * 5.0 + 9.0)).abs() < 1e-9, "{}", stock.volume());
        assert_eq!(stock.spans(1, 1).collect::<Vec<_>>(), vec![(0.0, 9.0)], "touching spans are one");
        assert_eq!(stock.spans(0, 0).collect::<Vec<_>>(), vec![(0.0, 2.0), (6.0, 9.0)]);
        // Bands and the flat form keep them.
        let again = DexelStock::join(DexelStock::all_from_flat(&DexelStock::all_to_flat(&stock.clone().split_rows(2))).unwrap());
        assert_eq!(again.lower, stock.lower);
        assert!((again.volume() - stock.volume()).abs() < 1e-9);
        let mut stock = again;
        // A flat end down to z = 4 over column (0, 0): its top span gone, the one under it its
        // top now (0–2), 3 mm³ removed; down to 1 over column (3, 3): 3 + 1 mm³.
        let cut = |stock: &mut DexelStock, at: DVec2, z: f64| stock.apply(&Sweep::line(Profile::new(0.25, 0.0), at.extend(z + 5.0), at.extend(z)));
        assert!((cut(&mut stock, DVec2::new(0.5, 0.5), 4.0) - 3.0).abs() < 1e-9);
        assert!((cut(&mut stock, DVec2::new(3.5, 3.5), 1.0) - 4.0).abs() < 1e-9);
        assert_eq!(stock.spans(0, 0).collect::<Vec<_>>(), vec![(0.0, 2.0)]);
        assert_eq!(stock.spans(3, 3).collect::<Vec<_>>(), vec![(0.0, 1.0)]);
        assert_eq!((stock.top(0, 0), stock.floor(0, 0)), (2.0, 0.0));
        // Cut into the cavity only: nothing more.
        assert_eq!(cut(&mut stock, DVec2::new(0.5, 0.5), 3.0), 0.0);
        assert!((stock.volume() - (15.0 * 5.0 + 9.0 - 7.0)).abs() < 1e-9, "{}", stock.volume());
    }
}

//! Feed moves over cleared ground at the air feed (the job's `stock.airFeed`; by default the
//! machine's rapid rate). A level's rings partly run over ground an earlier ring of the same
//! level took, its stay-down links cross it, and a region open to the air is approached from
//! beside the stock: at the cutting feed that is machine time in which nothing is removed
//! (issue 12's removal efficiency). Those stretches keep their place in the path (the tool
//! stays down, as a G1) and only run faster.
//!
//! The test is conservative against the program's own simulation (the in-process stock, seed
//! 002's z-map, whose cells stand for their centres, or a split cell's for its sub-cells') and
//! against the material itself: the level's material as a pixel on each cell's centre, set
//! where the cell's highest material stands above the level; a level move is air where no
//! material pixel lies within the cutter's radius grown by a margin of half a cell's diagonal
//! (a cell's material, and a sub-cell's centre, lie no farther from the cell's centre) of its
//! way, plus how far the stroke judged strays from the path; and it takes off the pixels
//! within its flat's radius less that margin (there it surely took every cell down to the
//! level, all of each). Ramps, helices and rapids take off nothing. So a stretch called air
//! removes nothing, and the verification holds it to that
//! ([`crate::sim::verify`]: a move faster than its tool's feed that removes material is an
//! error, as a rapid through stock is). A ball end (no flat) takes nothing off the map: its
//! levels leave scallops, and only ground untouched since the operation began counts as air.

use crate::cutter::Profile;
use crate::geom::segment::{Rect, Segment};
use crate::geom::tolerance::{FLOAT_SLACK, LEAST_STEP};
use crate::geom::{DVec2, DVec3};
use crate::sim::DexelStock;
use crate::toolpath::{arc_sweep, Move};
use crate::zigzag::load::PixelMap;

/// A stretch of air shorter than this (mm) stays at the cutting feed: a control would barely
/// reach the faster feed on it, and the program would change feed for nothing.
const SHORTEST: f64 = 2.0;
/// Pieces a level move is judged in, as pixels.
const PIECE_PIXELS: f64 = 4.0;

/// The material of one level, for telling which of its moves cut nothing.
pub struct AirCuts {
    map: PixelMap,
    /// Where the map holds the whole reach of a cutter whose centre stands here.
    inside: Rect,
    z: f64,
    /// The radius counted (the cutter's grown by the margin) and the one taken off (its flat's
    /// less the margin).
    count: f64,
    take: f64,
    piece: f64,
    pixel: f64,
    feed: f64,
}

/// One piece of a move: its move, the share of the move at its end, its length, where a
/// level move's piece starts and ends (and whether it stands for an arc, as its chord), and
/// whether it is air. A move that is not level is one piece, with no way: no stroke of air
/// runs through it.
struct Piece {
    mv: usize,
    t1: f64,
    length: f64,
    way: Option<(DVec2, DVec2, bool)>,
    air: bool,
}

/// One level's moves, from `from`, to be judged later against the material of `stock` above
/// `z` around `bounds` ([`AirCuts::new`], [`AirCuts::refeed`]): a job a second thread can take
/// while the next piece is planned (the stock is the operation's starting one, which planning
/// does not change).
pub struct Refeed<'m> {
    pub bounds: Rect,
    pub z: f64,
    pub stock: &'m DexelStock,
    pub profile: Profile,
    /// The air feed and the cutting one.
    pub feed: f64,
    pub cutting: f64,
    pub from: DVec3,
    pub moves: Vec<Move>,
}

impl Refeed<'_> {
    /// The moves with their stretches of air at the air feed.
    pub fn run(self) -> Vec<Move> {
        if self.moves.is_empty() {
            return self.moves;
        }
        match AirCuts::new(self.bounds, self.z, self.stock, &self.profile, self.feed, self.cutting) {
            Some(mut air) => air.refeed(self.from, self.moves),
            None => self.moves,
        }
    }
}

impl AirCuts {
    /// The material of `stock` above `z` around `bounds` (where the level's moves run), for a
    /// cutter of `profile` whose air moves run at `feed`; none where that is no faster than
    /// its `cutting` feed (nothing to change).
    pub fn new(bounds: Rect, z: f64, stock: &DexelStock, profile: &Profile, feed: f64, cutting: f64) -> Option<AirCuts> {
        if feed <= cutting {
            return None;
        }
        let px = stock.grid().spacing;
        let margin = std::f64::consts::FRAC_1_SQRT_2 * px;
        let count = profile.radius + margin;
        // The map reaches past its bounds by the radius counted and an arc's sag.
        let map = PixelMap::on_cells(stock, bounds.expand(count + 3.0 * px), z, count + px)?;
        Some(AirCuts { map, inside: bounds, z, count, take: profile.flat_radius() - margin, piece: PIECE_PIXELS * px, pixel: px, feed })
    }

    /// Whether the straight way from `a` to `b` cuts nothing, the path it stands for straying
    /// from it by `sag` at most; takes off what it surely cuts.
    fn air(&mut self, a: DVec2, b: DVec2, sag: f64) -> bool {
        let within = |p: DVec2| p.cmpge(self.inside.min).all() && p.cmple(self.inside.max).all();
        if self.map.count_past_at(a, b, self.count + sag, 0) == 0 {
            return within(a) && within(b);
        }
        if self.take - sag > 0.0 {
            self.map.cut_at(a, b, self.take - sag);
        }
        false
    }

    /// `moves` (starting at `from`) with every stretch of a level move that cuts nothing, and
    /// runs on for at least `SHORTEST` so, at the air feed; the others as they were. Takes
    /// what the level moves cut off the map.
    pub fn refeed(&mut self, from: DVec3, moves: Vec<Move>) -> Vec<Move> {
        // The level moves in pieces no longer than a piece (an arc's as chords within a
        // quarter pixel of it).
        let chord_sag = 0.25 * self.pixel;
        let mut pieces = Vec::new();
        let mut at = from;
        for (k, m) in moves.iter().enumerate() {
            let to = m.to();
            let level = !m.is_rapid() && (at.z - self.z).abs() < FLOAT_SLACK && (to.z - self.z).abs() < FLOAT_SLACK;
            if level {
                let length = m.length(at);
                let least = match *m {
                    Move::Arc { center, clockwise, .. } => {
                        let step = crate::geom::segment::chord_step(center.distance(at.truncate()), chord_sag).unwrap_or(std::f64::consts::FRAC_PI_2);
                        (arc_sweep(at, to, center, clockwise).abs() / step.max(LEAST_STEP)).ceil() as usize
                    }
                    _ => 1,
                };
                let n = least.max((length / self.piece).ceil() as usize).max(1);
                let arc = matches!(m, Move::Arc { .. });
                let mut prev = at.truncate();
                for i in 1..=n {
                    let t1 = i as f64 / n as f64;
                    let q = if i == n { to.truncate() } else { point(m, at, t1).truncate() };
                    pieces.push(Piece { mv: k, t1, length: length / n as f64, way: Some((prev, q, arc)), air: false });
                    prev = q;
                }
            } else {
                // A way through: pieces of air on either side are not one stretch.
                pieces.push(Piece { mv: k, t1: 1.0, length: 0.0, way: None, air: false });
            }
            at = to;
        }
        // Runs of pieces judged as one stroke, its chord within a quarter pixel of their ends
        // and no longer than two pieces: air all, or each cutting; each judged after those
        // before it have taken off what they surely cut.
        let mut i = 0;
        while i < pieces.len() {
            let Some((a, mut b, _)) = pieces[i].way else {
                i += 1;
                continue;
            };
            let mut j = i + 1;
            while j < pieces.len() {
                let Some((_, q, _)) = pieces[j].way else { break };
                let chord = Segment::line(a, q);
                if a.distance(q) > 2.0 * self.piece || pieces[i..=j].iter().filter_map(|p| p.way).any(|(_, p, _)| chord.distance_to(p) > chord_sag) {
                    break;
                }
                b = q;
                j += 1;
            }
            // How far the pieces stray from the stroke's chord: their ends, and an arc's chords
            // from the arc.
            let chord = Segment::line(a, b);
            let stroke = pieces[i..j].iter().filter_map(|p| p.way);
            let sag = stroke.clone().map(|(_, p, _)| chord.distance_to(p)).fold(0.0, f64::max) + if stroke.clone().any(|(_, _, arc)| arc) { chord_sag } else { 0.0 };
            let air = self.air(a, b, sag);
            pieces[i..j].iter_mut().for_each(|p| p.air = air);
            i = j;
        }
        // Stretches of air too short to be worth a change of feed stay at the cutting feed.
        let mut i = 0;
        while i < pieces.len() {
            let j = (i..pieces.len()).find(|&j| !pieces[j].air).unwrap_or(pieces.len());
            if pieces[i..j].iter().map(|p| p.length).sum::<f64>() < SHORTEST {
                pieces[i..j].iter_mut().for_each(|p| p.air = false);
            }
            i = j + 1;
        }
        let mut out = Vec::with_capacity(moves.len());
        let mut at = from;
        let mut p = 0;
        for (k, m) in moves.iter().enumerate() {
            let end = pieces[p..].iter().position(|q| q.mv != k).map_or(pieces.len(), |n| p + n);
            let mine = &pieces[p..end];
            p = end;
            if mine.iter().all(|q| !q.air) {
                out.push(*m);
            } else if mine.iter().all(|q| q.air) {
                out.push(with_feed(m, m.to(), self.feed));
            } else {
                // Runs of pieces alike, each as the move's own kind on its way.
                let mut s = 0;
                while s < mine.len() {
                    let e = (s..mine.len()).find(|&e| mine[e].air != mine[s].air).unwrap_or(mine.len());
                    let to = if e == mine.len() { m.to() } else { point(m, at, mine[e - 1].t1) };
                    out.push(with_feed(m, to, if mine[s].air { self.feed } else { m.feed().unwrap_or(f64::INFINITY) }));
                    s = e;
                }
            }
            at = m.to();
        }
        out
    }
}

/// The point of feed move `m` (starting at `from`) a share `t` of the way along it.
fn point(m: &Move, from: DVec3, t: f64) -> DVec3 {
    match *m {
        Move::Arc { to, center, clockwise, .. } => {
            let sweep = arc_sweep(from, to, center, clockwise);
            (center + DVec2::from_angle(sweep * t).rotate(from.truncate() - center)).extend(from.z + (to.z - from.z) * t)
        }
        _ => from.lerp(m.to(), t),
    }
}

/// Feed move `m` ending at `to` at `feed` (the faster of it and the move's own).
fn with_feed(m: &Move, to: DVec3, feed: f64) -> Move {
    match *m {
        Move::Line { feed: f, .. } => Move::Line { to, feed: feed.max(f) },
        Move::Arc { center, clockwise, feed: f, .. } => Move::Arc { to, center, clockwise, feed: feed.max(f) },
        Move::Rapid { .. } => Move::Rapid { to },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Aabb;
    use crate::sim::{StockModel, Sweep};

    #[test]
    fn what_a_level_cleared_is_crossed_at_the_air_feed_and_nothing_else() {
        let (z, cut, fast) = (-2.0, 1000.0, 5000.0);
        let mut stock = DexelStock::new(&Aabb { min: DVec3::new(-20.0, -20.0, -10.0), max: DVec3::new(20.0, 20.0, 0.0) }, 0.25, 1);
        let profile = Profile::new(3.0, 0.0);
        let p = |x: f64, y: f64| DVec3::new(x, y, z);
        let line = |x: f64, y: f64| Move::Line { to: p(x, y), feed: cut };
        let from = p(-15.0, -2.4);
        let moves = vec![
            // A channel in three passes 2.4 mm apart, then back along its middle (air) to an
            // arc that bulges past the channel's side: its chord lies in the channel, the arc
            // does not.
            line(15.0, -2.4),
            line(15.0, 0.0),
            line(-15.0, 0.0),
            line(-15.0, 2.4),
            line(15.0, 2.4),
            line(15.0, 0.0),
            line(4.0, 0.0),
            Move::Arc { to: p(-4.0, 0.0), center: DVec2::ZERO, clockwise: false, feed: cut },
            line(-15.0, 0.0),
            // Into the material, 1 mm back (air, too short to change feed for), on again.
            line(-15.0, 8.0),
            line(-15.0, 7.0),
            line(-15.0, 12.0),
        ];
        assert!(AirCuts::new(Rect { min: DVec2::splat(-17.0), max: DVec2::splat(17.0) }, z, &stock, &profile, cut, cut).is_none());
        let mut air = AirCuts::new(Rect { min: DVec2::splat(-17.0), max: DVec2::splat(17.0) }, z, &stock, &profile, fast, cut).unwrap();
        let out = air.refeed(from, moves.clone());
        // The same way: the same ends in order, as long.
        assert!((crate::toolpath::moves_length(from, &out) - crate::toolpath::moves_length(from, &moves)).abs() < 1e-9);
        let mut ends = out.iter().map(|m| m.to());
        assert!(moves.iter().all(|m| ends.any(|q| q.distance(m.to()) < 1e-12)), "{out:?}");
        // Cut in order: what runs at the air feed removes nothing, and most of the way back
        // along the slot does.
        let (mut at, mut air_length) = (from, 0.0);
        for m in &out {
            let removed: f64 = Sweep::of_move(profile, at, m, 1e-4).iter().map(|s| stock.apply(s)).sum();
            let feed = match *m {
                Move::Line { feed, .. } | Move::Arc { feed, .. } => feed,
                Move::Rapid { .. } => unreachable!(),
            };
            if feed == fast {
                assert!(removed == 0.0, "{m:?} at the air feed removed {removed} mm³");
                // The arc's ends lie in the channel, its top cuts past its side.
                assert!(!matches!(m, Move::Arc { .. }) || at.y.max(m.to().y) < 2.5, "{m:?} from {at} cuts past the channel");
                air_length += m.length(at);
            } else {
                assert_eq!(feed, cut);
            }
            if at.distance(p(-15.0, 8.0)) < 1e-12 {
                assert_eq!(feed, cut, "a 1 mm stretch of air keeps the cutting feed");
            }
            at = m.to();
        }
        assert!(air_length > 20.0, "{air_length} mm of 22 along the channel's middle at the air feed: {out:?}");
    }
}

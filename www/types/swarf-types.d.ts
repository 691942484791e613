// Generated from swarf's Rust types by ts-rs (tests/typescript.rs): do not edit.
// UPDATE_TYPES=1 cargo test --test typescript writes it anew.

/**
 * An axis-aligned box in millimetres.
 */
export type Aabb = { min: [number, number, number], max: [number, number, number], };

/**
 * What a form or a field is for.
 */
export type Applies = "part" | "drawing" | "either";

/**
 * How arcs are written.
 */
export type ArcFormat = "ij" | "r" | "off";

/**
 * Round bar stock ([`Stock::bar`]): the material a sawn length of bar holds, so that the
 * operations, the air-cut skipping and the verification see the air round it.
 */
export type Bar = { 
/**
 * The bar's diameter (mm). Default value: 50.
 */
diameter: number, 
/**
 * The axis it lies along: `z` stands it on end (a disc, a knob cut from its end), `x` or
 * `y` lays it in the vise. Default value: z.
 */
axis: BarAxis, };

/**
 * The axis of bar stock.
 */
export type BarAxis = "x" | "y" | "z";

/**
 * Helical boring of holes.
 */
export type Bore = { 
/**
 * Default value: "bore".
 */
name: string, 
/**
 * Whether the job runs it. Default value: true.
 */
enabled: boolean, 
/**
 * Default value: 1.
 */
tool: number, 
/**
 * Descent per turn of the helix (mm). Default value: 1.
 */
pitch: number, 
/**
 * Step between rings where the hole is more than twice the tool (fraction of the tool's
 * diameter). Default value: 0.4.
 */
stepoverFraction: number, 
/**
 * Material left on the wall (mm). Default value: 0.
 */
leaveStock: number, 
/**
 * The finishing pass's radial step (mm; 0: none): the wall is roughed this much short,
 * then finished climbing from the bottom. Default value: 0.
 */
finishStep: number, 
/**
 * Depth below each hole's top (mm). Default value: the hole's own (through: past its
 * bottom by the breakthrough).
 */
depth: number | null, 
/**
 * How far past a through hole's bottom (mm). Default value: 0.5.
 */
breakthrough: number, 
/**
 * Height above the material over the hole where the helix starts (mm). Default value: 1.
 */
retract: number, 
/**
 * Default value: climb.
 */
direction: Direction, 
/**
 * The holes, by their index as `swarf holes` (a part) or `swarf drawing` (a drawing's
 * loops) numbers them. Default value: all (within the diameters).
 */
holes: Array<number>, 
/**
 * Only holes at least this wide (mm). Default value: none.
 */
minDiameter: number | null, 
/**
 * Only holes at most this wide (mm). Default value: none.
 */
maxDiameter: number | null, 
/**
 * A drawing's drill marks (its POINTs) too, which "all the holes" leaves out: a DXF's points
 * are as often its dimensions' anchors as places to drill (a mark picked by number is
 * taken anyway). Default value: false.
 */
marks: boolean, 
/**
 * The height the operation's rapids cross at and its cycles start from (mm from
 * `clearanceFrom`), above the stock and the fixtures. Default value: none (the job's,
 * `stock.clearance` above the stock's top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The point a clearance `from: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * A blind hole's bottom.
 */
export type Bottom = "flat" | "cone" | "open";

/**
 * Where the tool's centre may go.
 */
export type Boundary = "stock" | "silhouette";

/**
 * Chamfering holes' edges.
 */
export type Chamfer = { 
/**
 * Default value: "chamfer".
 */
name: string, 
/**
 * Whether the job runs it. Default value: true.
 */
enabled: boolean, 
/**
 * A V-bit, chamfer mill or spot drill. Default value: 1.
 */
tool: number, 
/**
 * The chamfer's width at the top (mm, measured out from the hole's edge). Default value: 0.5.
 */
width: number, 
/**
 * How far below the chamfer's foot the tip goes, so the cone's side cuts the edge (mm).
 * Default value: 0.2.
 */
extraDepth: number, 
/**
 * Height above the material over the hole where feeding starts (mm). Default value: 1.
 */
retract: number, 
/**
 * Default value: climb.
 */
direction: Direction, 
/**
 * Which edges: the holes' (picked as above), or a drawing's loops (on `layers`, or those
 * named in `loops`). Default value: holes.
 */
edges: ChamferEdges, 
/**
 * A drawing's layers whose loops to chamfer (edges: loops). Default value: all.
 */
layers: Array<string>, 
/**
 * The drawing's loops to chamfer, by index as `swarf drawing` lists them (edges: loops).
 * Default value: all on the layers.
 */
loops: Array<number>, 
/**
 * The angle a loop's chamfer is entered at, along the loop (degrees). Default value: 10.
 */
rampAngle: number, 
/**
 * The holes, by their index as `swarf holes` (a part) or `swarf drawing` (a drawing's
 * loops) numbers them. Default value: all (within the diameters).
 */
holes: Array<number>, 
/**
 * Only holes at least this wide (mm). Default value: none.
 */
minDiameter: number | null, 
/**
 * Only holes at most this wide (mm). Default value: none.
 */
maxDiameter: number | null, 
/**
 * A drawing's drill marks (its POINTs) too, which "all the holes" leaves out: a DXF's points
 * are as often its dimensions' anchors as places to drill (a mark picked by number is
 * taken anyway). Default value: false.
 */
marks: boolean, 
/**
 * The height the operation's rapids cross at and its cycles start from (mm from
 * `clearanceFrom`), above the stock and the fixtures. Default value: none (the job's,
 * `stock.clearance` above the stock's top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The point a clearance `from: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * The edges a chamfer breaks.
 */
export type ChamferEdges = "holes" | "loops" | "partEdges";

/**
 * Which CL z-map builder an operation uses.
 */
export type ClBuilder = "exact" | "inverseOffset";

/**
 * The characters a control reads in comments.
 */
export type CommentCharacters = "ascii" | "any";

/**
 * How comments are written.
 */
export type CommentStyle = "parens" | "semicolon" | "none";

/**
 * Coolant for a tool.
 */
export type Coolant = "off" | "flood" | "mist";

/**
 * A tool's speeds and feeds as worked out, with the reasons in words.
 */
export type CuttingData = { tool: number, spindleRpm: number, feedRate: number, plungeRate: number, 
/**
 * Whether they come from the material (false: as typed).
 */
fromMaterial: boolean, 
/**
 * How they were worked out ("φ6 carbide, 2 flutes, in aluminium 6061: 244 m/min → …").
 */
reason: string, 
/**
 * Where the material's figures come from.
 */
source: string | null, };

/**
 * What a program takes on the machine, part by part: each tool path's motion (its way down
 * from the clearance height included), the tool changes, and the rest (the spindle's start
 * dwells and the retracts to the clearance height at tool changes and at the end). The parts
 * sum to the whole, and [`CycleTime::items`] rounds them so that they still do.
 */
export type CycleTime = { 
/**
 * Seconds of motion of each tool path, in the program's order.
 */
paths: Array<number>, 
/**
 * When each tool path's own moves begin (s from the program's start), after its tool
 * change and its way down from the clearance height.
 */
starts: Array<number>, toolChanges: number, 
/**
 * Seconds of the tool changes (`post.toolChangeSeconds` each).
 */
toolChangeSeconds: number, 
/**
 * Seconds of the rest: the spindle's start dwells and the retracts to the clearance
 * height at tool changes and at the program's end.
 */
otherSeconds: number, 
/**
 * The whole program (seconds): the sum of the parts.
 */
seconds: number, };

/**
 * The built-in posts, by the controller family they are written for.
 */
export type Dialect = "linuxCnc" | "grbl" | "grblHal" | "mach3" | "fanuc" | "generic";

/**
 * Cutting direction for a spindle turning clockwise (M3).
 */
export type Direction = "climb" | "conventional";

/**
 * Where a drawing is put.
 */
export type DrawingOrigin = "keep" | "lowerLeft" | "center";

/**
 * How a drawing becomes a sheet on the machine: the stock's top is Z0.
 */
export type DrawingSetup = { 
/**
 * Default value: file.
 */
units: DrawingUnits, 
/**
 * Default value: lower left.
 */
origin: DrawingOrigin, 
/**
 * Thickness of the sheet (mm). Default value: 6.
 */
thickness: number, };

/**
 * The units a drawing's numbers are in.
 */
export type DrawingUnits = "file" | "mm" | "inch";

/**
 * A drawing for the page's view: outer loops, holes and open chains as line segments at Z0
 * (xyz pairs), and a list of its loops and layers.
 */
export type DrawingView = { outer: Array<number>, holes: Array<number>, open: Array<number>, bounds: [number, number, number, number, number, number], loops: Array<LoopInfo>, layers: Array<string>, units: string, 
/**
 * What the reader left out, by kind, with how many.
 */
ignored: Array<[string, number]>, openChains: Array<OpenChain>, 
/**
 * A size that says the drawing was read in the wrong unit ([`job::drawing_unit_warning`]).
 */
warnings: Array<Warning>, };

/**
 * Drilling holes.
 */
export type Drill = { 
/**
 * Default value: "drill".
 */
name: string, 
/**
 * Whether the job runs it. Default value: true.
 */
enabled: boolean, 
/**
 * Default value: 1.
 */
tool: number, 
/**
 * Default value: drill.
 */
cycle: DrillCycle, 
/**
 * Depth below each hole's top (mm). Default value: the hole's own (through: past its
 * bottom by the drill's point and the breakthrough; a spot: the depth of a cone
 * `spotDiameter` across).
 */
depth: number | null, 
/**
 * How far the drill's full diameter goes past a through hole's bottom (mm). Default value: 0.5.
 */
breakthrough: number, 
/**
 * The spot's diameter at the top (mm). Default value: the hole's diameter, at most the tool's.
 */
spotDiameter: number | null, 
/**
 * Depth of each peck (mm; peck and chip break). Default value: 2.
 */
peck: number, 
/**
 * Seconds at the bottom (dwell). Default value: 0.5.
 */
dwell: number, 
/**
 * The R plane's height above the material over the hole (mm). Default value: 1.
 */
retract: number, 
/**
 * Default value: initial.
 */
returnTo: ReturnLevel, 
/**
 * The holes, by their index as `swarf holes` (a part) or `swarf drawing` (a drawing's
 * loops) numbers them. Default value: all (within the diameters).
 */
holes: Array<number>, 
/**
 * Only holes at least this wide (mm). Default value: none.
 */
minDiameter: number | null, 
/**
 * Only holes at most this wide (mm). Default value: none.
 */
maxDiameter: number | null, 
/**
 * A drawing's drill marks (its POINTs) too, which "all the holes" leaves out: a DXF's points
 * are as often its dimensions' anchors as places to drill (a mark picked by number is
 * taken anyway). Default value: false.
 */
marks: boolean, 
/**
 * The height the operation's rapids cross at and its cycles start from (mm from
 * `clearanceFrom`), above the stock and the fixtures. Default value: none (the job's,
 * `stock.clearance` above the stock's top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The point a clearance `from: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * Which drilling cycle.
 */
export type DrillCycle = "spot" | "drill" | "dwell" | "peck" | "chipBreak";

/**
 * A part's top edge as the page lists and draws it (`swarf edges`): numbered as the chamfer's
 * `loops` takes them (its place in the list).
 */
export type EdgeView = { 
/**
 * The height of the face it bounds (mm).
 */
z: number, 
/**
 * It drops down a steep wall all round: a chamfer can break it.
 */
sharp: boolean, 
/**
 * Its length (mm).
 */
length: number, 
/**
 * The loop's corners in plan (mm), closed back to the first.
 */
points: Array<[number, number]>, };

/**
 * The engagement angle of an operation's level cutting moves (those at one height that cut
 * more than a cell deep), as the simulation measured it, weighed by the moves' lengths: the
 * angle of the tool's circle inside the material, from the material's nearest edge `e` from
 * the move's path ([`crate::sim::verify::Verification::nearest`]: the nearest cut cell's
 * centre, less half a cell), the edge taken as parallel to the path on the side the material
 * lies (climb milling: the right). Along a line, `arccos(e / r)` (a straight cut `ae` into a
 * wall: `arccos(1 − ae/r)`); along an arc of radius ρ, where the edge is a circle about the
 * arc's centre, `arccos(e/r + (e² − r²)/(2ρr))` with the material outside it, ρ negative
 * with the material inside. A move whose nearest cut lies on its path (a slot, or more than
 * half the tool in the material) reads 90° or more: 90°.
 */
export type EngagementReport = { 
/**
 * The angle the operation holds (degrees).
 */
target: number, 
/**
 * The share of the cutting length within ±10 % of the target, and above 1.3× it.
 */
within: number, over: number, 
/**
 * The largest, the mean and the spread (standard deviation) by length (degrees).
 */
peak: number, mean: number, spread: number, 
/**
 * Each of the operation's moves' engagement (degrees; `null` where the move does not
 * count: rapids, ramps and helices, moves that cut a cell deep or less), for the plot.
 */
moves: Array<number | null>, };

/**
 * Engraving on a drawing.
 */
export type Engrave = { 
/**
 * Default value: "engrave".
 */
name: string, 
/**
 * Whether the job runs it. Default value: true.
 */
enabled: boolean, 
/**
 * Default value: 1.
 */
tool: number, 
/**
 * Depth below the sheet's top (mm). Default value: 0.5.
 */
depth: number, 
/**
 * Largest depth cut in one pass (mm). Default value: 0.5.
 */
stepdown: number, 
/**
 * Steepest descent along the line (degrees). Default value: 10.
 */
rampAngle: number, 
/**
 * Layers to engrave (empty: all). Default value: empty.
 */
layers: Array<string>, 
/**
 * Engrave the open chains on those layers. Default value: true.
 */
chains: boolean, 
/**
 * Closed loops to engrave, by their index (as `swarf drawing` numbers them). Default value: none.
 */
loops: Array<number>, 
/**
 * Engrave every closed loop on those layers too. Default value: false.
 */
allLoops: boolean, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where rapid descents stop and the feed begins (mm).
 * Default value: none (the job's, `stock.retract`).
 */
retract: number | null, 
/**
 * The point a clearance `from: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * How a cutter enters material.
 */
export type Entry = { 
/**
 * Steepest descent of a helix or ramp (degrees from horizontal). Default value: 3.
 */
rampAngle: number, 
/**
 * Smallest helix diameter, as a share of the tool's diameter. Default value: 0.3.
 */
helixMin: number, 
/**
 * Largest helix diameter, as a share of the tool's diameter. Default value: 0.9.
 */
helixMax: number, };

/**
 * How the tool enters material.
 */
export type EntryKind = "helix" | "ramp";

/**
 * Facing the stock's top.
 */
export type Face = { 
/**
 * Default value: "face".
 */
name: string, 
/**
 * Whether the job runs it. Default value: true.
 */
enabled: boolean, 
/**
 * A flat end mill or face mill. Default value: 1.
 */
tool: number, 
/**
 * How much to take off the stock's top (mm). Default value: down to the part's top.
 */
depth: number | null, 
/**
 * Largest depth cut in one level (mm). Default value: 1.
 */
stepdown: number, 
/**
 * Distance between passes (fraction of the tool's diameter, at most its flat). Default value: 0.7.
 */
stepoverFraction: number, 
/**
 * How far the tool reaches past the stock's outline (fraction of its diameter). Default value: 0.5.
 */
overlap: number, 
/**
 * Default value: zigzag.
 */
pattern: FacePattern, 
/**
 * A drawing's loops whose insides to face, as `swarf drawing` numbers them (the holes
 * inside them faced over); empty: the whole stock. Default value: empty.
 */
loops: Array<number>, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where rapid descents stop and the feed begins (mm).
 * Default value: none (the job's, `stock.retract`).
 */
retract: number | null, 
/**
 * The point a clearance `from: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * How a level is cleared.
 */
export type FacePattern = "zigzag" | "spiral";

/**
 * What the feed optimisation did (a job's `simulation.optimizeFeeds`, [`crate::sim::feeds`]).
 */
export type FeedReport = { 
/**
 * The program's time in motion at the feeds as planned, and as optimised (s; tool changes
 * apart).
 */
plain: number, seconds: number, 
/**
 * Cuts run faster for their thinner chips, moves that removed nothing run at the air feed,
 * and moves slowed after for the spindle's power.
 */
faster: number, aired: number, slowed: number, };

/**
 * One choice of a [`FieldInput::Choice`] field: its value in the job file and its words.
 */
export type FieldChoice = { value: string, label: string, };

/**
 * How a field is typed in.
 */
export type FieldInput = "number" | "int" | "choice" | "check" | "words" | "ints" | "text" | "tool";

/**
 * What a field holds, for its label and the page's units: a length and a feed follow the
 * page's mm or inches; the others are said as they are.
 */
export type FieldUnit = "none" | "length" | "feed" | "degrees" | "seconds";

/**
 * A place where something went wrong.
 */
export type Finding = { 
/**
 * Index of the move (in program order), when a move is to blame.
 */
moveIndex: number | null, at: [number, number, number], 
/**
 * Gouge depth, collision depth (mm), or the volume a rapid cut (mm³).
 */
amount: number, };

/**
 * Pencil finishing along the part's concave corners.
 */
export type FinishPencil = { 
/**
 * Shown in the program's comments. Default value: "pencil finish".
 */
name: string, 
/**
 * Whether the job runs it (a disabled operation stays in the job). Default value: true.
 */
enabled: boolean, 
/**
 * Number of the tool to use (a ball end mill). Default value: 1.
 */
tool: number, 
/**
 * The least bend of the tool's path across a corner that makes it a pencil line (degrees):
 * where the ball touches two faces at once, its path turns by their angle. Default value:
 * 20.
 */
bend: number, 
/**
 * Passes either side of each corner's, each a step-over farther from it across the
 * surface (closing round its ends): a wider band cleaned where a larger tool left a
 * fillet's width. Default value: 0 (the corner's pass alone).
 */
passes: number, 
/**
 * Distance between the parallel passes, measured across the surface (mm). Default value:
 * a fifth of the tool's diameter.
 */
stepover: number | null, 
/**
 * Material left on the part (mm). Default value: 0.
 */
allowance: number, 
/**
 * Spacing of the CL z-map (mm): the corners are found to about half of it. Default value:
 * 0.1.
 */
grid: number, 
/**
 * Lowest tip height where the part is not under the tool (mm). Default value: stock bottom.
 */
floor: number | null, 
/**
 * Longest link that may stay down (mm). Default value: the tool's diameter.
 */
stayDownMax: number | null, 
/**
 * How the cutter enters material (helix, else ramp along the pass).
 */
entry: Entry, 
/**
 * Cut only where the stock the earlier operations left stands above what this one
 * leaves (by more than the job's gouge tolerance). Default value: false.
 */
restOnly: boolean, 
/**
 * The highest the tool's tip cuts (mm from `topFrom`): a roughing's first level is a
 * step-down below it, a finishing leaves what lies above it. Default value: none (the
 * stock's top).
 */
top: number | null, 
/**
 * What `top` is measured from. Default value: stockTop.
 */
topFrom: HeightFrom, 
/**
 * The lowest the tool's tip goes (mm from `bottomFrom`): the operation stops there, over
 * the part and beside it, as one side of a part machined from both stops at its parting
 * line and leaves the rest joined to the stock the vise grips. Default value: none (the
 * stock's bottom; the parting line itself where `bottomFrom` is `partingLine`).
 */
bottom: number | null, 
/**
 * What `bottom` is measured from. Default value: zero.
 */
bottomFrom: HeightFrom, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where the operation's rapid descents stop and the feed
 * begins, and over which its short retracts travel (mm). Default value: none (the job's,
 * `stock.retract`).
 */
retract: number | null, 
/**
 * The point a height `…From: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates, as the page picks it on the part it shows. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * Raster finishing over the CL z-map (seed 001).
 */
export type FinishRaster = { 
/**
 * Shown in the program's comments. Default value: "raster finish".
 */
name: string, 
/**
 * Whether the job runs it (a disabled operation stays in the job). Default value: true.
 */
enabled: boolean, 
/**
 * Number of the tool to use. Default value: 1.
 */
tool: number, 
/**
 * Direction of the passes (degrees from +X). Default value: 0.
 */
angle: number, 
/**
 * Distance between passes (mm). Default value: 0.5.
 */
stepover: number, 
/**
 * Default value: zigzag.
 */
pattern: Pattern, 
/**
 * Default value: silhouette.
 */
boundary: Boundary, 
/**
 * Growth of the silhouette boundary (mm). Default value: the tool's radius.
 */
margin: number | null, 
/**
 * Material left on the part (mm). Default value: 0.
 */
allowance: number, 
/**
 * Spacing of the CL z-map (mm). Default value: 0.25.
 */
grid: number, 
/**
 * Default value: exact.
 */
builder: ClBuilder, 
/**
 * Lowest tip height where the part is not under the tool (mm). Default value: stock bottom.
 */
floor: number | null, 
/**
 * Longest link that may stay down (mm). Default value: twice the stepover.
 */
stayDownMax: number | null, 
/**
 * How the cutter enters material (helix, else ramp along the pass).
 */
entry: Entry, 
/**
 * Cut only where the stock the earlier operations left stands above what this one
 * leaves (by more than the job's gouge tolerance). Default value: false.
 */
restOnly: boolean, 
/**
 * Only where the surface is no steeper than this (degrees from horizontal; waterline
 * finishing takes the steeper areas). Default value: none (everywhere).
 */
slopeMax: number | null, 
/**
 * The highest the tool's tip cuts (mm from `topFrom`): a roughing's first level is a
 * step-down below it, a finishing leaves what lies above it. Default value: none (the
 * stock's top).
 */
top: number | null, 
/**
 * What `top` is measured from. Default value: stockTop.
 */
topFrom: HeightFrom, 
/**
 * The lowest the tool's tip goes (mm from `bottomFrom`): the operation stops there, over
 * the part and beside it, as one side of a part machined from both stops at its parting
 * line and leaves the rest joined to the stock the vise grips. Default value: none (the
 * stock's bottom; the parting line itself where `bottomFrom` is `partingLine`).
 */
bottom: number | null, 
/**
 * What `bottom` is measured from. Default value: zero.
 */
bottomFrom: HeightFrom, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where the operation's rapid descents stop and the feed
 * begins, and over which its short retracts travel (mm). Default value: none (the job's,
 * `stock.retract`).
 */
retract: number | null, 
/**
 * The point a height `…From: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates, as the page picks it on the part it shows. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * Scallop finishing: passes a step apart over the surface for a given cusp height.
 */
export type FinishScallop = { 
/**
 * Shown in the program's comments. Default value: "scallop finish".
 */
name: string, 
/**
 * Whether the job runs it (a disabled operation stays in the job). Default value: true.
 */
enabled: boolean, 
/**
 * Number of the tool to use (a ball or bull-nose end mill). Default value: 1.
 */
tool: number, 
/**
 * Height of the ridge left between two passes (mm): the step between them follows from
 * it and the tool's radius, measured across the surface. Default value: 0.01.
 */
cusp: number, 
/**
 * Default value: silhouette.
 */
boundary: Boundary, 
/**
 * Growth of the silhouette boundary (mm). Default value: the tool's radius.
 */
margin: number | null, 
/**
 * Material left on the part (mm). Default value: 0.
 */
allowance: number, 
/**
 * Spacing of the CL z-map (mm). Default value: 0.2.
 */
grid: number, 
/**
 * Lowest tip height where the part is not under the tool (mm). Default value: stock bottom.
 */
floor: number | null, 
/**
 * Longest link that may stay down (mm). Default value: twice the step.
 */
stayDownMax: number | null, 
/**
 * How the cutter enters material (helix, else ramp along the pass).
 */
entry: Entry, 
/**
 * Cut only where the stock the earlier operations left stands above what this one
 * leaves (by more than the job's gouge tolerance). Default value: false.
 */
restOnly: boolean, 
/**
 * Only where the surface is no steeper than this (degrees from horizontal). Default
 * value: none (everywhere).
 */
slopeMax: number | null, 
/**
 * The highest the tool's tip cuts (mm from `topFrom`): a roughing's first level is a
 * step-down below it, a finishing leaves what lies above it. Default value: none (the
 * stock's top).
 */
top: number | null, 
/**
 * What `top` is measured from. Default value: stockTop.
 */
topFrom: HeightFrom, 
/**
 * The lowest the tool's tip goes (mm from `bottomFrom`): the operation stops there, over
 * the part and beside it, as one side of a part machined from both stops at its parting
 * line and leaves the rest joined to the stock the vise grips. Default value: none (the
 * stock's bottom; the parting line itself where `bottomFrom` is `partingLine`).
 */
bottom: number | null, 
/**
 * What `bottom` is measured from. Default value: zero.
 */
bottomFrom: HeightFrom, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where the operation's rapid descents stop and the feed
 * begins, and over which its short retracts travel (mm). Default value: none (the job's,
 * `stock.retract`).
 */
retract: number | null, 
/**
 * The point a height `…From: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates, as the page picks it on the part it shows. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * Steep-and-shallow finishing: waterline on the steep, scallop or raster on the shallow.
 */
export type FinishSteepShallow = { 
/**
 * Shown in the program's comments. Default value: "steep and shallow finish".
 */
name: string, 
/**
 * Whether the job runs it (a disabled operation stays in the job). Default value: true.
 */
enabled: boolean, 
/**
 * Number of the tool to use (a ball or bull-nose end mill). Default value: 1.
 */
tool: number, 
/**
 * Height of the ridge left between passes and between levels (mm). Default value: 0.01.
 */
cusp: number, 
/**
 * Where steep begins (degrees from horizontal): waterline above it, the shallow passes
 * below. Default value: 40.
 */
slope: number, 
/**
 * How far each zone reaches into the other (mm), so no seam is left. Default value: 0.5.
 */
overlap: number, 
/**
 * Default value: scallop.
 */
shallow: Shallow, 
/**
 * Direction of the raster passes (degrees from +X). Default value: 0.
 */
angle: number, 
/**
 * The waterlines' direction. Default value: climb.
 */
direction: Direction, 
/**
 * Default value: silhouette.
 */
boundary: Boundary, 
/**
 * Growth of the silhouette boundary (mm). Default value: the tool's radius.
 */
margin: number | null, 
/**
 * Material left on the part (mm). Default value: 0.
 */
allowance: number, 
/**
 * Spacing of the CL z-map (mm). Default value: 0.2.
 */
grid: number, 
/**
 * How the cutter enters material (helix, else ramp along the pass).
 */
entry: Entry, 
/**
 * Cut only where the stock the earlier operations left stands above what this one
 * leaves (by more than the job's gouge tolerance). Default value: false.
 */
restOnly: boolean, 
/**
 * The highest the tool's tip cuts (mm from `topFrom`): a roughing's first level is a
 * step-down below it, a finishing leaves what lies above it. Default value: none (the
 * stock's top).
 */
top: number | null, 
/**
 * What `top` is measured from. Default value: stockTop.
 */
topFrom: HeightFrom, 
/**
 * The lowest the tool's tip goes (mm from `bottomFrom`): the operation stops there, over
 * the part and beside it, as one side of a part machined from both stops at its parting
 * line and leaves the rest joined to the stock the vise grips. Default value: none (the
 * stock's bottom; the parting line itself where `bottomFrom` is `partingLine`).
 */
bottom: number | null, 
/**
 * What `bottom` is measured from. Default value: zero.
 */
bottomFrom: HeightFrom, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where the operation's rapid descents stop and the feed
 * begins, and over which its short retracts travel (mm). Default value: none (the job's,
 * `stock.retract`).
 */
retract: number | null, 
/**
 * The point a height `…From: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates, as the page picks it on the part it shows. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * Waterline finishing.
 */
export type FinishWaterline = { 
/**
 * Default value: "waterline finish".
 */
name: string, 
/**
 * Whether the job runs it (a disabled operation stays in the job). Default value: true.
 */
enabled: boolean, 
/**
 * Default value: 1.
 */
tool: number, 
/**
 * Height between levels (mm); used when `scallop` is not set. Default value: 0.5.
 */
stepdown: number, 
/**
 * Largest scallop height between levels (mm, at least 0.001): levels closer where the surface is
 * shallower. Default value: none (the step-down).
 */
scallop: number | null, 
/**
 * Material left on the part (mm). Default value: 0.
 */
allowance: number, 
/**
 * Only where the surface is steeper than this (degrees from horizontal). Default value: 30.
 */
slopeMin: number, 
/**
 * Default value: climb.
 */
direction: Direction, 
/**
 * Spacing of the CL z-map (mm). Default value: 0.25.
 */
grid: number, entry: Entry, 
/**
 * Cut only where the stock the earlier operations left stands above what this one
 * leaves (by more than the job's gouge tolerance): after a larger ball, a smaller one
 * takes only the corners it left. Default value: false.
 */
restOnly: boolean, 
/**
 * The highest the tool's tip cuts (mm from `topFrom`): a roughing's first level is a
 * step-down below it, a finishing leaves what lies above it. Default value: none (the
 * stock's top).
 */
top: number | null, 
/**
 * What `top` is measured from. Default value: stockTop.
 */
topFrom: HeightFrom, 
/**
 * The lowest the tool's tip goes (mm from `bottomFrom`): the operation stops there, over
 * the part and beside it, as one side of a part machined from both stops at its parting
 * line and leaves the rest joined to the stock the vise grips. Default value: none (the
 * stock's bottom; the parting line itself where `bottomFrom` is `partingLine`).
 */
bottom: number | null, 
/**
 * What `bottom` is measured from. Default value: zero.
 */
bottomFrom: HeightFrom, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where the operation's rapid descents stop and the feed
 * begins, and over which its short retracts travel (mm). Default value: none (the job's,
 * `stock.retract`).
 */
retract: number | null, 
/**
 * The point a height `…From: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates, as the page picks it on the part it shows. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * A box no tool may enter: a clamp, a plate, a stop.
 */
export type FixtureBox = { 
/**
 * Its name, in the messages. Default value: "fixture N".
 */
name: string, 
/**
 * Its least corner (mm, in the program's coordinates). Default value: [0, 0, 0].
 */
min: [number, number, number], 
/**
 * Its greatest corner. Default value: [0, 0, 0].
 */
max: [number, number, number], };

/**
 * A move into a fixture's clearance: which fixture, which tool, where and how deep.
 */
export type FixtureCollision = { fixture: string, tool: number, finding: Finding, };

/**
 * A fixture as a mesh.
 */
export type FixtureMesh = { 
/**
 * Its name, in the messages. Default value: its file's name.
 */
name: string, 
/**
 * Its file (STL, OBJ, glTF), in the program's coordinates (mm).
 */
file: MeshFile, };

/**
 * What holds the stock in a setup.
 */
export type Fixtures = { 
/**
 * A vise gripping the stock's sides; its jaws follow the stock. Default value: none.
 */
vise: Vise | null, 
/**
 * Clamps, a plate, anything else: boxes in the program's coordinates (mm from the work
 * zero). Default value: none.
 */
boxes: Array<FixtureBox>, 
/**
 * Fixtures as meshes (a vise's model, a strap clamp, a soft jaw), in the program's
 * coordinates (mm from the work zero): the operations keep out of the box round each,
 * the verification out of the mesh itself. Default value: none.
 */
meshes: Array<FixtureMesh>, 
/**
 * How far every tool keeps from each of them (mm). Default value: 1.
 */
clearance: number, 
/**
 * The part is held by something the fixtures do not show (screws, tape, a vacuum table,
 * soft jaws on its finished faces): an operation that cuts it free of what the fixtures
 * grip (or, without fixtures, of the stock round it) is then noted, not refused or warned
 * of. Default value: false.
 */
heldOtherwise: boolean, };

/**
 * How a setup turns the part over from the setup before it (the first: from the part as
 * placed), about an axis through the stock's centre, as a machinist turns it in the vise.
 */
export type Flip = "none" | "aboutX" | "aboutY";

/**
 * One field of an operation's form.
 */
export type FormField = { 
/**
 * The setting it edits, dotted into objects (`tabs.count`).
 */
key: string, 
/**
 * Its words, without the unit ("Step-down").
 */
label: string, input: FieldInput, unit: FieldUnit, 
/**
 * What the number means beyond its unit ("fraction of the tool's diameter").
 */
note: string | null, 
/**
 * What an empty field means ("down to the part's top"); none: it must be filled.
 */
empty: string | null, 
/**
 * The least and the most it takes (in mm for a length).
 */
min: number | null, max: number | null, 
/**
 * The choices of a [`FieldInput::Choice`].
 */
choices: Array<FieldChoice>, 
/**
 * A longer word on what it does (the field's tooltip).
 */
help: string | null, 
/**
 * Shown for a part, a drawing or either.
 */
applies: Applies, };

/**
 * Which way the thread turns.
 */
export type Hand = "right" | "left";

/**
 * What a height given on an operation is measured from (its `bottomFrom`), as Fusion's
 * Heights tab has them: the setup's work zero, the stock's top or bottom, or the part's top or
 * bottom as the setup holds it.
 */
export type HeightFrom = "zero" | "stockTop" | "stockBottom" | "partTop" | "partBottom" | "partingLine" | "point";

/**
 * A holder: its sections from the face the tool stands out of (the collet nut's) upward.
 */
export type Holder = { 
/**
 * Shown in the library and on the setup sheet. Default value: "holder".
 */
name: string, 
/**
 * From the nut's face up. Default value: one section 30 mm wide and 20 mm long.
 */
sections: Array<HolderSection>, };

/**
 * One section of a holder: a cylinder, or a cone whose top is `topDiameter` wide.
 */
export type HolderSection = { 
/**
 * Its diameter at its bottom (mm). Default value: 30.
 */
diameter: number, 
/**
 * Its length up the tool's axis (mm). Default value: 20.
 */
length: number, 
/**
 * A cone's diameter at its top (mm). Default value: as at its bottom (a cylinder).
 */
topDiameter: number | null, };

/**
 * A round vertical hole.
 */
export type Hole = { 
/**
 * Centre (mm).
 */
center: [number, number], diameter: number, 
/**
 * Where the hole starts and ends (Z, mm); a drawing's holes go through the sheet.
 */
top: number, bottom: number, 
/**
 * Open at the bottom.
 */
through: boolean, 
/**
 * How its bottom ends where it is blind: flat, or a cone (a drill's point).
 */
bottomShape: Bottom, 
/**
 * The number `swarf drawing` lists a drawing's hole by: its loop's, or for a drill mark the
 * number after the loops (the loops' count plus the mark's place among the marks).
 */
loopIndex: number | null, 
/**
 * The drawing's layer, for a drawing's hole.
 */
layer: string | null, 
/**
 * A drill mark (a DXF POINT): a place to drill with no diameter of its own (`diameter` is
 * 0); drilling makes it as wide as its drill, and the operations that need a hole's size
 * (bore, chamfer, thread) refuse it.
 */
mark: boolean, };

/**
 * The tools read from a library, and what of it was not taken.
 */
export type Imported = { tools: Array<Tool>, 
/**
 * What the file holds that swarf did not take, each said once.
 */
notes: Array<string>, };

/**
 * Everything needed to turn a part into G-code.
 */
export type Job = { 
/**
 * Version of the job file's format ([`JOB_VERSION`] when written by this swarf); a file
 * without one is read as version 1. Default value: the current version.
 */
version: number, 
/**
 * Program title. Default value: "swarf job".
 */
name: string, part: PartSetup, 
/**
 * How a DXF or SVG drawing is placed (ignored for parts).
 */
drawing: DrawingSetup, stock: Stock, tools: Array<Tool>, operations: Array<Operation>, post: PostSettings, simulation: Simulation, tolerances: Tolerances, 
/**
 * The part machined from more than one side: each setup holds it its own way up, with
 * its own work offset and operations, and starts from the stock the one before left
 * ([`crate::job::setups`]). Empty: the job is one setup, its `operations`. Default value:
 * none.
 */
setups: Array<Setup>, 
/**
 * What holds the stock (a vise, clamps), kept out of by every operation and checked
 * against every move ([`crate::job::fixtures`]); a setup may name its own. Default value:
 * none.
 */
fixtures: Fixtures, 
/**
 * The machine's limits: its spindle's speed range and fastest feed, which the speeds and
 * feeds from the material keep to. Default value: a hobby router (8000–24000 rpm, 5000
 * mm/min).
 */
machine: Machine, };

/**
 * How much a [`Warning`] asks of the user.
 */
export type Level = "warning" | "note";

/**
 * The formats a library is written in.
 */
export type LibraryFormat = "fusion" | "linuxCnc";

/**
 * Line numbers (N words). A number never comes back: a program with more lines than `start`
 * and `step` reach before `max` is numbered by ones, and one with more lines than that is
 * numbered up to `max` and goes on unnumbered (a control reads a line without an N word; one
 * that reads a number twice may jump to the wrong line).
 */
export type LineNumbers = { start: number, step: number, 
/**
 * The largest number the control reads.
 */
max: number, };

/**
 * How the load is held at the reference.
 */
export type LoadControl = "path" | "feed" | "none";

/**
 * The load along one operation's path, before and after its correction, relative to the
 * reference (seed 004 Fig. 14): for reports and the page's plot.
 */
export type LoadReport = { 
/**
 * The reference rate at the tool's feed (mm³/min per mm of depth: step-over × feed).
 */
reference: number, 
/**
 * The same at a full step-down (mm³/min): the reference line of the page's MRR plot.
 */
rate: number, 
/**
 * Δs (mm).
 */
sampling: number, 
/**
 * Per window of Δs along the cutting moves, the plain path's load over the reference.
 */
plain: Array<number>, 
/**
 * The same for the path as cut (the tool's engagement).
 */
load: Array<number>, 
/**
 * The path as cut, at its feeds: the removal rate over the reference rate.
 */
cut: Array<number>, 
/**
 * The length of path (mm) that runs at a lowered feed because no extra path eases it.
 */
slowed: number, };

/**
 * One closed loop of a drawing, as the page lists it.
 */
export type LoopInfo = { index: number, layer: string, hole: boolean, entities: number, min: [number, number], max: [number, number], 
/**
 * Its line segments: vertices `lines[0]..lines[1]` (in pairs) of `holes` or `outer`.
 */
lines: [number, number], };

/**
 * The machine's limits the speeds and feeds keep to.
 */
export type Machine = { 
/**
 * Shown in the page and on the setup sheet. Default value: "hobby router".
 */
name: string, 
/**
 * The spindle's slowest and fastest speeds (rpm). Default value: 8000 and 24000.
 */
spindleMin: number, spindleMax: number, 
/**
 * The fastest cutting feed (mm/min). Default value: 5000.
 */
maxFeed: number, 
/**
 * How far the machine travels in X, Y and Z (mm): a program that spans more in any axis
 * cannot run on it, and is marked not safe to run, naming where. Default value: none (not
 * known: not checked; each built-in machine has its own).
 */
travel: [number, number, number] | null, 
/**
 * Rapid rates in X, Y and Z (mm/min): a rapid takes as long as its slowest axis needs,
 * in the cycle time and the setup sheet. Default value: none (not known: rapids are timed
 * along the move at the post's `rapidRate`; each built-in machine has its own).
 */
rapids: [number, number, number] | null, 
/**
 * The spindle's power (kW): where the stock's material has a specific cutting force
 * (the metals), the feeds are held down wherever the simulation finds a cut taking more
 * ([`MACHINE_COEFFICIENT`] of it reaching the cut). Default value: none (not known: not
 * held; each built-in machine has its own).
 */
power: number | null, 
/**
 * Whether it changes tools itself (`T… M6` fetches the tool). Without one the operator
 * changes each tool by hand where the program stops, told which to put in. Default value:
 * none (not known: the program as the post writes it; each built-in machine says).
 */
toolChanger: boolean | null, 
/**
 * Whether it has a tool length sensor (a tool setter): after a change by hand the new
 * tool's length is measured on it (the control's or the sender's tool change routine),
 * instead of the operator touching off Z again. Default value: none (not known; each
 * built-in machine says).
 */
lengthSensor: boolean | null, };

/**
 * The stock's material.
 */
export type Material = "aluminium6061" | "mildSteel" | "stainless304" | "brass" | "acrylic" | "hdpe" | "hardwood" | "mdf" | "plywood";

/**
 * A material as the page lists it.
 */
export type MaterialChoice = { value: Material, words: string, source: string, };

/**
 * A mesh file in the job: its name (the extension tells the format) and its bytes.
 */
export type MeshFile = { 
/**
 * The file's name, with its extension. Default value: "".
 */
name: string, 
/**
 * Its bytes in base64; none: the file lies beside the job file under `name` (the CLI
 * reads it). Default value: none.
 */
data: string | null, };

/**
 * Where a chain of segments failed to close.
 */
export type OpenChain = { layer: string, start: [number, number], end: [number, number], segments: number, };

/**
 * One operation of a job.
 */
export type Operation = { "kind": "roughZlevel" } & RoughZlevel | { "kind": "roughZigzag" } & RoughZigzag | { "kind": "roughAdaptive" } & RoughAdaptive | { "kind": "roughOctree" } & RoughOctree | { "kind": "finishRaster" } & FinishRaster | { "kind": "finishWaterline" } & FinishWaterline | { "kind": "finishPencil" } & FinishPencil | { "kind": "finishScallop" } & FinishScallop | { "kind": "finishSteepShallow" } & FinishSteepShallow | { "kind": "profile2d" } & Profile2d | { "kind": "pocket2d" } & Pocket2d | { "kind": "engrave" } & Engrave | { "kind": "drill" } & Drill | { "kind": "bore" } & Bore | { "kind": "chamfer" } & Chamfer | { "kind": "threadMill" } & ThreadMill | { "kind": "face" } & Face | { "kind": "vcarve" } & VCarve;

/**
 * An operation's form.
 */
export type OperationForm = { 
/**
 * The kind, as the job file names it.
 */
kind: string, 
/**
 * Its name in the list of operations to add ("face the stock's top").
 */
title: string, 
/**
 * A paragraph shown over its fields.
 */
hint: string | null, applies: Applies, picks: Picks | null, fields: Array<FormField>, 
/**
 * Settings of the job file the form leaves out (set in the file only).
 */
keptOut: Array<string>, };

/**
 * One operation's figures.
 */
export type OperationReport = { 
/**
 * Its index in the job's operations.
 */
index: number, name: string, 
/**
 * The tools it used, in order.
 */
tools: Array<number>, moves: number, 
/**
 * Time at the programmed feeds and the rapid rate (s).
 */
seconds: number, feedLength: number, rapidLength: number, 
/**
 * Volume removed (mm³), when its moves were simulated.
 */
removed: number | null, 
/**
 * Largest material removal rate of its feed moves (mm³/min), when simulated.
 */
mrrMax: number | null, 
/**
 * The spindle power its heaviest cut takes (kW: [`crate::cutting::power`] of `mrrMax`),
 * where the stock's material has a specific cutting force.
 */
powerMax: number | null, 
/**
 * The thickest chip a tooth cut (mm per tooth, measured: [`crate::sim::feeds::chips`]),
 * when simulated.
 */
chipMax: number | null, 
/**
 * Material left above the part plus the allowance after it, largest and mean over the
 * part (mm), when the program was verified.
 */
leftMax: number | null, leftMean: number | null, 
/**
 * The load along its path against the reference, before and after seed 004's correction,
 * where the operation measured it.
 */
load: LoadReport | null, 
/**
 * The stages of an operation that chose its tools (seed 000): each tool, why, and what it did.
 */
stages: Array<StageReport> | null, 
/**
 * The engagement along its cut as the simulation measured it, where it holds one
 * (adaptive clearing).
 */
engagement: EngagementReport | null, 
/**
 * For a roughing after earlier work with larger tools (rest roughing: it cuts only what
 * they left, the in-process stock), those tools, largest first; `removed` is what it took
 * of their leftovers.
 */
restAfter: Array<number>, };

/**
 * The order a level-by-level roughing cuts in (`order` of z-level roughing).
 */
export type Order = "regions" | "levels";

/**
 * How to read a part's coordinates.
 */
export type PartSetup = { 
/**
 * Unit of the file's coordinates. Default value: auto (metres for glTF, else mm).
 */
units: PartUnits, 
/**
 * A free factor on top of the unit (a model made at half size: 2). Default value: 1.
 */
scale: number, 
/**
 * The file's up axis. Default value: z.
 */
upAxis: UpAxis, 
/**
 * A turn about Z after that, in degrees counterclockwise seen from above: 0, 90, 180 or
 * 270. Default value: 0.
 */
rotation: number, 
/**
 * Where the part goes. Default value: centerTop.
 */
placement: Placement, };

/**
 * The unit of a part file's coordinates.
 */
export type PartUnits = "auto" | "mm" | "inch" | "m";

/**
 * How spans are cut.
 */
export type Passes = "zigzag" | "oneWay";

/**
 * How consecutive passes run.
 */
export type Pattern = "zigzag" | "oneWay";

/**
 * What the page finds for an operation to pick from, shown above its fields.
 */
export type Picks = "holes";

/**
 * Where the part goes.
 */
export type Placement = "centerTop" | "keep";

/**
 * Pocket operation on a drawing.
 */
export type Pocket2d = { 
/**
 * Default value: "pocket".
 */
name: string, 
/**
 * Whether the job runs it (a disabled operation stays in the job). Default value: true.
 */
enabled: boolean, 
/**
 * Default value: 1.
 */
tool: number, 
/**
 * Depth below the stock top (mm). Default value: 3.
 */
depth: number, 
/**
 * Largest depth cut in one pass (mm). Default value: 1.
 */
stepdown: number, 
/**
 * Distance between rings or passes as a fraction of the tool diameter. Default value: 0.4.
 */
stepoverFraction: number, 
/**
 * Material left on walls and islands (mm). Default value: 0.
 */
leaveStock: number, 
/**
 * Default value: offset.
 */
pattern: PocketPattern, 
/**
 * Direction of zigzag passes (degrees from +X). Default value: 0.
 */
angle: number, 
/**
 * How the zigzag pattern holds the tool's load at the step-over's (seed 004 §3). Default
 * value: path.
 */
load: LoadControl, 
/**
 * How far over the reference load a zigzag step may go (0.1: 10 %). Default value: 0.1.
 */
loadTolerance: number, 
/**
 * Default value: helix.
 */
entry: EntryKind, 
/**
 * Helix radius (mm). Default value: 0.4 × the tool diameter.
 */
helixRadius: number | null, 
/**
 * Steepest descent of helices and ramps (degrees). Default value: 3.
 */
rampAngle: number, 
/**
 * Default value: climb.
 */
direction: Direction, 
/**
 * Layers to pocket (empty: all). Default value: empty.
 */
layers: Array<string>, 
/**
 * Indices of the drawing's loops bounding the pocket, with the holes inside them as
 * islands (empty: all). Default value: empty.
 */
loops: Array<number>, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where rapid descents stop and the feed begins (mm).
 * Default value: none (the job's, `stock.retract`).
 */
retract: number | null, 
/**
 * The point a clearance `from: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * How the pocket is cleared.
 */
export type PocketPattern = "offset" | "zigzag" | "adaptive";

/**
 * A post-processor. A field left out takes the generic post's value.
 */
export type Post = { 
/**
 * Shown in the page and written in the program's head.
 */
name: string, 
/**
 * The file extension its controllers expect (`ngc`, `tap`, `nc`).
 */
extension: string, 
/**
 * Lines before everything else (`%`, a program number `O{program} ({title})`).
 */
header: Array<string>, 
/**
 * Modal setup lines, written after the units word (G20/G21).
 */
setup: Array<string>, 
/**
 * The work offset to select (`G54` … `G59`, and those of `workOffsets`), or none.
 */
workOffset: string | null, 
/**
 * The work offsets the control has beyond `G54` to `G59`. Default value: none.
 */
workOffsets: WorkOffsets, 
/**
 * Lines that change the tool (`T{tool} M6`, `G43 H{tool}`). Empty: the control has no tool
 * changer, and the program stops the spindle, names the tool in a comment and pauses.
 */
toolChange: Array<string>, 
/**
 * The pause for a manual tool change (`M0`).
 */
pause: string, 
/**
 * Starts the spindle clockwise (`S{rpm} M3`).
 */
spindleOn: string, spindleOff: string, 
/**
 * Coolant words (`M8`, `M7`, `M9`); a tool asking for one the post lacks is refused.
 */
coolantFlood: string | null, coolantMist: string | null, coolantOff: string | null, 
/**
 * A dwell (`G4 P{seconds}`; Fanuc `G4 P{millis}`).
 */
dwell: string | null, 
/**
 * Seconds to wait after starting the spindle (0: none). Needs `dwell`.
 */
spindleDwell: number, comments: CommentStyle, 
/**
 * The characters its comments may hold; others are transliterated. Default value: ascii.
 */
commentCharacters: CommentCharacters, lineNumbers: LineNumbers | null, 
/**
 * Digits after the point for lengths in millimetres and in inches, and for feeds.
 */
decimalsMm: number, decimalsInch: number, feedDecimals: number, arcs: ArcFormat, 
/**
 * Split arcs where they cross a quadrant (0°, 90°, 180°, 270°), for controls that want
 * arcs of at most 90°.
 */
arcQuadrants: boolean, 
/**
 * Arcs may move Z (helices); without, a helix is written as chords.
 */
helix: boolean, 
/**
 * The largest radius written as an arc (mm); a larger one (a curve bowing a hair over its
 * length) is written as chords within [`ARC_CHORD_ERROR`]. GRBL computes arcs in
 * float32, which holds a centre 2.7 km off to a quarter of a millimetre: its posts set 2 m.
 * Default value: 100,000 (100 m, for controls computing in double).
 */
maxArcRadius: number, 
/**
 * Leave out a motion word or coordinate that has not changed.
 */
modal: boolean, 
/**
 * The control runs the drilling cycles G81, G82, G83 and G73 (with R, Q, P, G98/G99 and
 * G80): a drilling operation's holes are written as those; without (GRBL 1.1), as the
 * moves they make.
 */
cannedCycles: boolean, 
/**
 * The longest line the control reads (characters), or none. Comments are shortened to
 * fit; a motion that cannot fit is an error.
 */
maxLineLength: number | null, 
/**
 * Lines after the program's last retract and spindle stop (`M2`, `M30`, `%`).
 */
footer: Array<string>, };

/**
 * How G-code is written.
 */
export type PostSettings = { 
/**
 * The built-in post. Default value: linuxCnc.
 */
dialect: Dialect, 
/**
 * A post of the user's own (the fields of [`Post`]), used instead of the built-in one.
 * Default value: none.
 */
custom: Post | null, 
/**
 * Units of the program. Default value: mm.
 */
units: Units, 
/**
 * Digits after the decimal point, instead of the post's. Default value: the post's (3
 * for mm, 4 for inches in the built-in posts).
 */
decimals: number | null, 
/**
 * Rapid rate of the machine (mm/min), for the cycle-time estimate. Default value: 3000.
 */
rapidRate: number, 
/**
 * Time a tool change takes (seconds), for the cycle-time estimate. Default value: 15.
 */
toolChangeSeconds: number, 
/**
 * Program number (O word) for posts that write one. Default value: 1.
 */
programNumber: number, 
/**
 * The work offset the program selects (`G54` to `G59`), instead of the post's: each
 * setup of a part holds its own zero. Default value: the post's (G54 in the built-in
 * posts).
 */
workOffset: string | null, 
/**
 * With setups: every setup in one program, the control stopping (the post's pause, `M0`)
 * between them with a message on how to hold the part next, instead of a program per
 * setup. Default value: false.
 */
oneProgram: boolean, };

/**
 * A setting of a job that does not fit: its path in the job and the whole message.
 */
export type Problem = { 
/**
 * The field's path (`operations[0].stepdown`, `stock.marginXy`).
 */
path: string, 
/**
 * What is wrong: naming the field (as the CLI says it), or, as `checkJob` gives it for a
 * page that shows it at the field, without the path ([`Problem::at_field`]).
 */
message: string, };

/**
 * Profile operation on a drawing.
 */
export type Profile2d = { 
/**
 * Default value: "profile".
 */
name: string, 
/**
 * Whether the job runs it (a disabled operation stays in the job). Default value: true.
 */
enabled: boolean, 
/**
 * Default value: 1.
 */
tool: number, 
/**
 * Default value: auto.
 */
side: Side, 
/**
 * Default value: climb.
 */
direction: Direction, 
/**
 * Depth below the stock top (mm). Default value: the stock's thickness plus 0.2 (through).
 */
depth: number | null, 
/**
 * Largest depth cut in one lap (mm). Default value: 2.
 */
stepdown: number, 
/**
 * Material left on the walls (mm). Default value: 0.
 */
leaveStock: number, 
/**
 * Radius of the lead-in and lead-out arcs (mm; 0 for none). Default value: the tool radius.
 */
leadRadius: number | null, 
/**
 * Steepest descent along the contour (degrees). Default value: 3.
 */
rampAngle: number, tabs: Tabs, 
/**
 * Layers to cut (empty: all). Default value: empty.
 */
layers: Array<string>, 
/**
 * Indices of the drawing's loops to cut (empty: all on the layers). Default value: empty.
 */
loops: Array<number>, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where rapid descents stop and the feed begins (mm).
 * Default value: none (the job's, `stock.retract`).
 */
retract: number | null, 
/**
 * The point a clearance `from: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * A project: a job and its part or drawing.
 */
export type Project = { format: string, version: number, job: Job, workpiece: ProjectFile, };

/**
 * The part or drawing of a project.
 */
export type ProjectFile = { 
/**
 * The file's name, with its extension (it tells the format).
 */
name: string, 
/**
 * The file's bytes in base64; none: the file lies beside the project under `name`.
 */
data?: string | null, };

/**
 * The verification report with a text for people.
 */
export type ReportView = { text: string, cells: number, moves: number, 
/**
 * Volume removed by the whole program (mm³).
 */
removed: number, gougeCount: number, 
/**
 * Deepest gouge (mm), 0 when none.
 */
gougeMax: number, gouges: Array<Finding>, rapidCollisionCount: number, rapidCollisions: Array<Finding>, bodyCollisionCount: number, bodyCollisions: Array<Finding>, 
/**
 * Moves that drive the tool's holder into material (how deep past its face), where the
 * tool has a holder.
 */
holderCollisionCount: number, holderCollisions: Array<Finding>, 
/**
 * Moves into what holds the stock, grown by its clearance ([`super::fixtures`]); none
 * checked where the job names no fixtures (`fixtures_checked`).
 */
fixturesChecked: number, fixtureCollisionCount: number, fixtureCollisions: Array<FixtureCollision>, 
/**
 * Largest and mean material above part + allowance where the part is (mm).
 */
residualMax: number, residualMean: number, 
/**
 * Largest material removal rate of the feed moves (mm³/min), each measured over
 * [`RATE_CELLS`] cells of path ([`removal_rates`]).
 */
mrrMax: number, 
/**
 * The gouges on the walls of the part's round holes in a machinist's words
 * ([`hole_overcuts`]: "φ6.4 drill (T2) in φ6.35 holes: 0.025 mm oversize on the radius").
 */
overcuts: Array<string>, };

/**
 * A program written again for another post.
 */
export type Reposted = { gcode: string, extension: string, post: string, cycle: CycleTime, time: Array<TimeItem>, };

/**
 * How retracts between cuts travel ([`Stock::retracts`]).
 */
export type Retracts = "minimum" | "full";

/**
 * Where the tool goes between holes.
 */
export type ReturnLevel = "initial" | "retract";

/**
 * Adaptive roughing.
 */
export type RoughAdaptive = { 
/**
 * Default value: "adaptive rough".
 */
name: string, 
/**
 * Whether the job runs it (a disabled operation stays in the job). Default value: true.
 */
enabled: boolean, 
/**
 * The tool that cuts every level. Default value: 1.
 */
tool: number, 
/**
 * Largest depth between levels (mm): up to the flute length. Default value: 6.
 */
stepdown: number, 
/**
 * The optimal load: the radial engagement as a fraction of the tool diameter, held all
 * along the path. Default value: 0.1.
 */
stepoverFraction: number, 
/**
 * Helix radius (mm). Default value: 0.4 × the tool diameter.
 */
helixRadius: number | null, 
/**
 * The shortest step of the path (mm), where it turns: each step's heading is searched
 * there for the target engagement (shorter or longer than the default, passes end sooner:
 * BENCHMARKS.md). Default value: 0.1 × the tool's radius (at most half the radius; no
 * finer than two pixels of the map the engagement is read on).
 */
minStep: number | null, 
/**
 * The longest step of the path (mm), along a run that holds the engagement at one
 * curvature (a spiral, a wall): a step there is twice the last, up to this, and the
 * shortest again where the engagement no longer holds. Default value: 0.1 × the tool's
 * radius, or the shortest step where that is longer (at most half the radius).
 */
maxStep: number | null, 
/**
 * Cut every flat area of the part at its own height too. Default value: true.
 */
flats: boolean, 
/**
 * Which comes first: each region down to its floor before the next (`regions`), or each
 * level everywhere before the next (`levels`). Default value: regions.
 */
order: Order, 
/**
 * Material left on floors (axial, mm). Default value: 0.5.
 */
allowance: number, 
/**
 * Material left on walls (radial, mm). Default value: 0.5.
 */
leaveStock: number, 
/**
 * Default value: climb.
 */
direction: Direction, 
/**
 * Spacing of the CL z-map (mm). Default value: 0.25.
 */
grid: number, 
/**
 * Steepest descent of helices and ramps (degrees). Default value: 3.
 */
rampAngle: number, 
/**
 * Rest roughing: plan against what the earlier operations left (the in-process stock),
 * so that after a larger tool only its leftovers are cut and no air it cleared; off, plan
 * against the setup's stock as it came, as if nothing had been cut. Default value: true.
 */
rest: boolean, 
/**
 * The highest the tool's tip cuts (mm from `topFrom`): a roughing's first level is a
 * step-down below it, a finishing leaves what lies above it. Default value: none (the
 * stock's top).
 */
top: number | null, 
/**
 * What `top` is measured from. Default value: stockTop.
 */
topFrom: HeightFrom, 
/**
 * The lowest the tool's tip goes (mm from `bottomFrom`): the operation stops there, over
 * the part and beside it, as one side of a part machined from both stops at its parting
 * line and leaves the rest joined to the stock the vise grips. Default value: none (the
 * stock's bottom; the parting line itself where `bottomFrom` is `partingLine`).
 */
bottom: number | null, 
/**
 * What `bottom` is measured from. Default value: zero.
 */
bottomFrom: HeightFrom, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where the operation's rapid descents stop and the feed
 * begins, and over which its short retracts travel (mm). Default value: none (the job's,
 * `stock.retract`).
 */
retract: number | null, 
/**
 * The point a height `…From: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates, as the page picks it on the part it shows. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * Octree multi-tool roughing.
 */
export type RoughOctree = { 
/**
 * Default value: "octree rough".
 */
name: string, 
/**
 * Whether the job runs it. Default value: true.
 */
enabled: boolean, 
/**
 * The tools it may choose from, by number. Default value: empty, meaning every flat and
 * bull-nose end in the job's library.
 */
tools: Array<number>, 
/**
 * Axial depth of cut as a fraction of each tool's diameter (seed 000's δ = h / D), at least
 * 0.01 and never more than the tool's flute length. Default value: 0.25.
 */
delta: number, 
/**
 * Distance between rings after the first as a fraction of the tool's diameter, at most
 * 0.85 (seed 000 §3.3: wider steps leave islands where boundaries meet at 90°). The paper's
 * regions are unions of square octants; here they follow the part, and rings more than
 * the tool's radius apart can leave strips where a region narrows
 * ([`crate::machining::rings::rings`]), so the default is the widest that never does. Default
 * value: 0.5.
 */
stepoverFraction: number, 
/**
 * Material left on floors (axial, mm). Default value: 0.5.
 */
allowance: number, 
/**
 * Material left on walls (radial, mm). Default value: 0.5.
 */
leaveStock: number, 
/**
 * Default value: climb.
 */
direction: Direction, 
/**
 * Spacing of the CL z-map (mm). Default value: 0.25.
 */
grid: number, 
/**
 * Steepest descent of helices and ramps (degrees). Default value: 3.
 */
rampAngle: number, 
/**
 * Rest roughing: plan against what the earlier operations left (the in-process stock),
 * so that after a larger tool only its leftovers are cut and no air it cleared; off, plan
 * against the setup's stock as it came, as if nothing had been cut. Default value: true.
 */
rest: boolean, 
/**
 * The highest the tool's tip cuts (mm from `topFrom`): a roughing's first level is a
 * step-down below it, a finishing leaves what lies above it. Default value: none (the
 * stock's top).
 */
top: number | null, 
/**
 * What `top` is measured from. Default value: stockTop.
 */
topFrom: HeightFrom, 
/**
 * The lowest the tool's tip goes (mm from `bottomFrom`): the operation stops there, over
 * the part and beside it, as one side of a part machined from both stops at its parting
 * line and leaves the rest joined to the stock the vise grips. Default value: none (the
 * stock's bottom; the parting line itself where `bottomFrom` is `partingLine`).
 */
bottom: number | null, 
/**
 * What `bottom` is measured from. Default value: zero.
 */
bottomFrom: HeightFrom, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where the operation's rapid descents stop and the feed
 * begins, and over which its short retracts travel (mm). Default value: none (the job's,
 * `stock.retract`).
 */
retract: number | null, 
/**
 * The point a height `…From: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates, as the page picks it on the part it shows. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * Zigzag roughing (seed 004).
 */
export type RoughZigzag = { 
/**
 * Default value: "zigzag rough".
 */
name: string, 
/**
 * Whether the job runs it (a disabled operation stays in the job). Default value: true.
 */
enabled: boolean, 
/**
 * The tool that cuts the passes. Default value: 1.
 */
tool: number, 
/**
 * Direction of the passes (degrees from +X). Default value: 0.
 */
angle: number, 
/**
 * Default value: zigzag.
 */
passes: Passes, 
/**
 * Default value: path.
 */
load: LoadControl, 
/**
 * How far over the reference a stretch of Δs may load the tool (0.1: 10 %). Default value: 0.1.
 */
loadTolerance: number, 
/**
 * The sampling distance Δs (mm). Default value: half the step-over.
 */
sampling: number | null, 
/**
 * The pixel of the load's map (mm), at most an eighth of the step-over. Default value: the
 * step-over / 24.
 */
pixel: number | null, 
/**
 * Cut every flat area of the part at its own height too. Default value: true.
 */
flats: boolean, 
/**
 * Largest depth between levels (mm). Default value: 2.
 */
stepdown: number, 
/**
 * Distance between rings or passes as a fraction of the tool diameter. Default value: 0.4.
 */
stepoverFraction: number, 
/**
 * Material left on floors (axial, mm). Default value: 0.5.
 */
allowance: number, 
/**
 * Material left on walls (radial, mm). Default value: 0.5.
 */
leaveStock: number, 
/**
 * Default value: climb.
 */
direction: Direction, 
/**
 * Spacing of the CL z-map (mm). Default value: 0.25.
 */
grid: number, 
/**
 * Steepest descent of helices and ramps (degrees). Default value: 3.
 */
rampAngle: number, 
/**
 * Rest roughing: plan against what the earlier operations left (the in-process stock),
 * so that after a larger tool only its leftovers are cut and no air it cleared; off, plan
 * against the setup's stock as it came, as if nothing had been cut. Default value: true.
 */
rest: boolean, 
/**
 * The highest the tool's tip cuts (mm from `topFrom`): a roughing's first level is a
 * step-down below it, a finishing leaves what lies above it. Default value: none (the
 * stock's top).
 */
top: number | null, 
/**
 * What `top` is measured from. Default value: stockTop.
 */
topFrom: HeightFrom, 
/**
 * The lowest the tool's tip goes (mm from `bottomFrom`): the operation stops there, over
 * the part and beside it, as one side of a part machined from both stops at its parting
 * line and leaves the rest joined to the stock the vise grips. Default value: none (the
 * stock's bottom; the parting line itself where `bottomFrom` is `partingLine`).
 */
bottom: number | null, 
/**
 * What `bottom` is measured from. Default value: zero.
 */
bottomFrom: HeightFrom, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where the operation's rapid descents stop and the feed
 * begins, and over which its short retracts travel (mm). Default value: none (the job's,
 * `stock.retract`).
 */
retract: number | null, 
/**
 * The point a height `…From: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates, as the page picks it on the part it shows. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * Z-level roughing.
 */
export type RoughZlevel = { 
/**
 * Default value: "z-level rough".
 */
name: string, 
/**
 * Whether the job runs it (a disabled operation stays in the job). Default value: true.
 */
enabled: boolean, 
/**
 * The tool that cuts every level. Default value: 1.
 */
tool: number, 
/**
 * Helix radius (mm). Default value: 0.4 × the tool diameter.
 */
helixRadius: number | null, 
/**
 * Cut every flat area of the part at its own height too. Default value: true.
 */
flats: boolean, 
/**
 * Which comes first: each region down to its floor before the next (`regions`: the tool
 * goes from pocket to pocket once, not once per level), or each level everywhere before
 * the next (`levels`). Default value: regions.
 */
order: Order, 
/**
 * Largest depth between levels (mm). Default value: 2.
 */
stepdown: number, 
/**
 * Distance between rings or passes as a fraction of the tool diameter. Default value: 0.4.
 */
stepoverFraction: number, 
/**
 * Material left on floors (axial, mm). Default value: 0.5.
 */
allowance: number, 
/**
 * Material left on walls (radial, mm). Default value: 0.5.
 */
leaveStock: number, 
/**
 * Default value: climb.
 */
direction: Direction, 
/**
 * Spacing of the CL z-map (mm). Default value: 0.25.
 */
grid: number, 
/**
 * Steepest descent of helices and ramps (degrees). Default value: 3.
 */
rampAngle: number, 
/**
 * Rest roughing: plan against what the earlier operations left (the in-process stock),
 * so that after a larger tool only its leftovers are cut and no air it cleared; off, plan
 * against the setup's stock as it came, as if nothing had been cut. Default value: true.
 */
rest: boolean, 
/**
 * The highest the tool's tip cuts (mm from `topFrom`): a roughing's first level is a
 * step-down below it, a finishing leaves what lies above it. Default value: none (the
 * stock's top).
 */
top: number | null, 
/**
 * What `top` is measured from. Default value: stockTop.
 */
topFrom: HeightFrom, 
/**
 * The lowest the tool's tip goes (mm from `bottomFrom`): the operation stops there, over
 * the part and beside it, as one side of a part machined from both stops at its parting
 * line and leaves the rest joined to the stock the vise grips. Default value: none (the
 * stock's bottom; the parting line itself where `bottomFrom` is `partingLine`).
 */
bottom: number | null, 
/**
 * What `bottom` is measured from. Default value: zero.
 */
bottomFrom: HeightFrom, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where the operation's rapid descents stop and the feed
 * begins, and over which its short retracts travel (mm). Default value: none (the job's,
 * `stock.retract`).
 */
retract: number | null, 
/**
 * The point a height `…From: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates, as the page picks it on the part it shows. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * One setup of a part machined from more than one side.
 */
export type Setup = { 
/**
 * Its name, in its program's name and on its setup sheet. Default value: "Setup N".
 */
name: string, 
/**
 * How the part is turned over from the setup before. Default value: none.
 */
flip: Flip, 
/**
 * Which face of the part it holds up, whatever the setups before did (instead of a
 * `flip` from the setup before): `+z` its top, `-z` its bottom, `+x`, `-x`, `+y`, `-y` a
 * side, the part stood on the opposite one. Default value: none (as `flip` says).
 */
up: Up | null, 
/**
 * Then a turn about the spindle, counter-clockwise seen from above (degrees: 0, 90, 180
 * or 270). Default value: 0.
 */
turn: number, 
/**
 * The work offset its program selects: `G54` to `G59`, or one the control has besides
 * (`G59.1` to `G59.3` on LinuxCNC and grblHAL, `G54.1 P1` to `G54.1 P48` on Fanuc).
 * Default value: the job's post's.
 */
workOffset: string | null, 
/**
 * The point of the stock, as this setup holds it, that is its program's origin. Default
 * value: the job's `stock.zero`.
 */
zero: WorkZero | null, 
/**
 * What this setup cuts, in order. Default value: none.
 */
operations: Array<Operation>, 
/**
 * What holds the stock in this setup. Default value: the job's `fixtures`.
 */
fixtures: Fixtures | null, };

/**
 * Where a setup holds the part, for the view and a portal: a point `p` of the part as the job
 * places it is at `rotation · (p − centre) + centre + shift` in the setup (the rotation by
 * quarter turns, column after column); `stock` is the raw stock's box there.
 */
export type SetupView = { index: number, name: string, rotation: [number, number, number, number, number, number, number, number, number], centre: [number, number, number], shift: [number, number, number], stock: Aabb, 
/**
 * What holds the stock in it (a vise's jaws, clamps, fixtures as meshes by their boxes):
 * each box's least and greatest corner.
 */
fixtures: Array<[number, number, number, number, number, number]>, };

/**
 * What finishes the shallow ground.
 */
export type Shallow = "scallop" | "raster";

/**
 * The shape of a cutter's end.
 */
export type Shape = "flat" | "ball" | "bullNose" | "drill" | "spotDrill" | "vBit" | "threadMill";

/**
 * Which side of a loop the tool runs on.
 */
export type Side = "auto" | "outside" | "inside";

/**
 * Simulating the program after it is made (seed 002), to verify it and to show the cut.
 */
export type Simulation = { 
/**
 * Simulate and verify every program. Default value: true.
 */
verify: boolean, 
/**
 * Cell size of the simulated stock (mm). Default value: the size that gives the stock
 * about a million cells, and no smaller than 0.05 mm.
 */
cell: number | null, 
/**
 * Feeds along the path from what the simulation measured: each cut's feed raised for its
 * chip's thinning, up to its tool's chip load and under the air feed, and each move that
 * removes nothing at the air feed ([`crate::sim::feeds::speed_up`]). Default value: false.
 */
optimizeFeeds: boolean, };

/**
 * Where a tool's spindle speed and feeds come from.
 */
export type Speeds = "fromMaterial" | "asTyped";

/**
 * One stage of octree roughing: its tool, why, and what it did.
 */
export type StageReport = { tool: number, diameter: number, role: StageRole, 
/**
 * Side of the octants matched to the tool (mm); none for profiling.
 */
side: number | null, 
/**
 * d / D.
 */
gamma: number | null, 
/**
 * Axial depth of cut (mm).
 */
depth: number, 
/**
 * Why this tool, for a person.
 */
why: string, 
/**
 * Area of the XY plane where the stage removed material (mm²).
 */
area: number, 
/**
 * Volume it removed (mm³).
 */
removed: number, 
/**
 * Machine time at its feeds and the rapid rate (s).
 */
seconds: number, };

/**
 * Why a stage's tool was chosen.
 */
export type StageRole = "first" | "octants" | "profile" | "rest";

/**
 * The stock, as a machinist sets it: margins around the placed part on every side, or an
 * explicit box; the heights of moves between cuts; and the work zero.
 */
export type Stock = { 
/**
 * Extra stock around the part in X and Y (mm, each side). Default value: 5.
 */
marginXy: number, 
/**
 * Extra stock above the part's top (mm). Default value: 1.
 */
marginTop: number, 
/**
 * Extra stock below the part's bottom (mm). Default value: 0.
 */
marginBottom: number, 
/**
 * Margins on each side in X and Y, `[left (-X), right (+X), front (-Y), back (+Y)]` (mm),
 * instead of `marginXy`. Default value: none.
 */
marginSides: [number, number, number, number] | null, 
/**
 * The stock as an explicit box (mm, where the part is placed), instead of margins.
 * Default value: none.
 */
sizeBox: Aabb | null, 
/**
 * Height above the stock top for rapid moves where they cannot go lower (mm): the start
 * and end of each operation, and retracts over stock standing that high. Default value: 5.
 */
clearance: number, 
/**
 * Gap above the material under the tool where a rapid descent stops and the feed begins,
 * and above the material on the way where a retract travels across (mm): the short
 * retract. Default value: 1.
 */
retract: number, 
/**
 * How a retract between two cuts travels across: `minimum`, the retract gap above the
 * highest material on the way (the clearance where the stock stands that high); `full`,
 * at the clearance height, over clamps and fixtures the stock does not show (a z-level
 * roughing still crosses what it has cleared just above its levels). Default value:
 * minimum.
 */
retracts: Retracts, 
/**
 * Feed (mm/min) of the moves a roughing or pocket level knows cut nothing: stretches of
 * rings over ground an earlier ring of the level took, stay-down links across it, the way
 * in from beside the stock. They stay in the path (the tool down, as G1), only faster, and
 * the verification holds each to cutting nothing. At most the rapid rate and the machine's fastest feed; no faster than
 * the tool's feed keeps them at it. Default value: the post's rapid rate.
 */
airFeed: number | null, 
/**
 * Moves part and stock so that this point is the program's origin (for parts; a sheet's
 * top is always Z0). Default value: none (as the part's placement puts it).
 */
zero: WorkZero | null, 
/**
 * Round bar stock instead of a box: its diameter and the axis it lies along, centred on
 * the part, as long as the part and the margins along its axis (the margins across it
 * are the bar's). Default value: none.
 */
bar: Bar | null, 
/**
 * What the stock is: the tools' speeds and feeds follow from it ([`crate::cutting`]).
 * Default value: none (every tool's as typed).
 */
material: Material | null, 
/**
 * A mesh as the stock instead of a box: a casting or a near-net blank, in the part's own
 * coordinates (both from one CAD model), placed with the part; its box is the stock's
 * ([`super::blank`]). Default value: none.
 */
mesh: MeshFile | null, };

/**
 * What the page shows of a job's result beside the drawing: figures, warnings, the problem if
 * any, the per-operation reports and the cycle time's breakdown.
 */
export type Summary = { warnings: Array<Warning>, 
/**
 * Per operation: name, tools, time, lengths, volume removed, peak MRR, what it left.
 */
operations: Array<OperationReport>, 
/**
 * The index of each operation's first move in the program (for the scrubber's marks).
 */
operationStarts: Array<number>, 
/**
 * Lookups of the CL z-map cache that found a z-map made for an earlier operation.
 */
cacheHits: number, 
/**
 * What makes the program unsafe to run, if verification found anything.
 */
problem: string | null, stock: [number, number, number, number, number, number], 
/**
 * What holds the stock (a vise's jaws, clamps): each box's least and greatest corner.
 */
fixtures: Array<[number, number, number, number, number, number]>, clearanceZ: number, 
/**
 * The extension the post's controllers expect of the program's file.
 */
extension: string, 
/**
 * The post's name, for the program's file name.
 */
post: string, 
/**
 * The program's cycle time as its head states it (tool changes included).
 */
cycle: CycleTime, 
/**
 * The cycle time by operation, tool changes and the rest, in whole seconds summing to the
 * whole, as the program's head and the CLI give it.
 */
time: Array<TimeItem>, 
/**
 * What the feed optimisation did, where the job asked for it.
 */
feeds: FeedReport | null, moves: number, feedLength: number, rapidLength: number, 
/**
 * Estimated cycle time (seconds) at the programmed feeds and the given rapid rate.
 */
seconds: number, };

/**
 * Holding tabs for parts cut through the sheet.
 */
export type Tabs = { 
/**
 * Tabs per outside loop (0: none, unless `spacing` is set). Default value: 0.
 */
count: number, 
/**
 * Distance between tabs along the path (mm); used when `count` is 0. Default value: none.
 */
spacing: number | null, 
/**
 * Length of material left along the part's edge (mm). Default value: 4.
 */
width: number, 
/**
 * Height of the tab above the sheet's bottom (above the cut's floor where the cut stops
 * inside the sheet), mm: the material that holds the part. Default value: 1.5.
 */
height: number, };

/**
 * Milling internal threads.
 */
export type ThreadMill = { 
/**
 * Default value: "thread".
 */
name: string, 
/**
 * Whether the job runs it. Default value: true.
 */
enabled: boolean, 
/**
 * A thread mill. Default value: 1.
 */
tool: number, 
/**
 * The thread's name: M8, M8x1, 1/4-20, #10-32, 1/4 UNC. Default value: M6.
 */
thread: string, 
/**
 * The major diameter (mm), instead of the name's. Default value: none.
 */
majorDiameter: number | null, 
/**
 * The pitch (mm), instead of the name's. Default value: none.
 */
pitch: number | null, 
/**
 * Default value: right.
 */
hand: Hand, 
/**
 * Radial passes to the full depth. Default value: 1.
 */
passes: number, 
/**
 * How deep the thread goes below the hole's top (mm). Default value: the hole's depth.
 */
length: number | null, 
/**
 * Height above the material over the hole the tool enters from (mm). Default value: 1.
 */
retract: number, 
/**
 * An external thread, on a part's round boss (a stud turned or milled to the major
 * diameter, cleared round), picked as `swarf holes --bosses` lists them: the tool comes
 * down beside it and goes round it clockwise (climb: down for a right-hand thread, up for a
 * left-hand one). Default value: false (internal, in holes).
 */
external: boolean, 
/**
 * The holes, by their index as `swarf holes` (a part) or `swarf drawing` (a drawing's
 * loops) numbers them. Default value: all (within the diameters).
 */
holes: Array<number>, 
/**
 * Only holes at least this wide (mm). Default value: none.
 */
minDiameter: number | null, 
/**
 * Only holes at most this wide (mm). Default value: none.
 */
maxDiameter: number | null, 
/**
 * A drawing's drill marks (its POINTs) too, which "all the holes" leaves out: a DXF's points
 * are as often its dimensions' anchors as places to drill (a mark picked by number is
 * taken anyway). Default value: false.
 */
marks: boolean, 
/**
 * The height the operation's rapids cross at and its cycles start from (mm from
 * `clearanceFrom`), above the stock and the fixtures. Default value: none (the job's,
 * `stock.clearance` above the stock's top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The point a clearance `from: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * One part of a program's cycle time, for people: what it is and how long it takes.
 */
export type TimeItem = { label: string, 
/**
 * Whole seconds.
 */
seconds: number, };

/**
 * Distances in millimetres.
 */
export type Tolerances = { 
/**
 * Triangles with an area below `degenerate_area` (mm²) are dropped at import and counted.
 * Default value: 1e-12.
 */
degenerateArea: number, 
/**
 * Largest distance a reduced tool path may lie above the points it replaces (chordal
 * tolerance of point reduction, mm). It never lies below them. Default value: 0.002.
 */
chordal: number, 
/**
 * Heights closer than this are treated as equal when deciding whether a linking move
 * may stay down (mm). Default value: 1e-6.
 */
height: number, 
/**
 * Largest distance of the exact CL surface from the straight line between two points of a
 * path where the height was computed exactly, as tested at the midpoint by subdivision
 * (mm). Where one feature decides both ends the rise between is at most twice this
 * (`zmap/surface.rs` gives the argument). Default value: 0.0005.
 */
interpolation: number, 
/**
 * Horizontal components of a unit normal below this make a facet horizontal; normals
 * with a vertical component below it make a facet vertical. Default value: 1e-12.
 */
normal: number, 
/**
 * Verification reports material below the part's surface plus allowance as a gouge only
 * when it is deeper than this (mm); the same margin applies to the tool body's clearance.
 * Default value: 0.02.
 */
gouge: number, 
/**
 * End points of drawn entities closer than this are joined into one chain (mm).
 * Default value: 0.01.
 */
chain: number, 
/**
 * Curves (splines, ellipses, Béziers) are replaced by arcs that stay within this distance
 * of them (mm). Default value: 0.002.
 */
arcFit: number, 
/**
 * Entities of a loop shorter than this are merged into their neighbours before and after
 * offsetting, as seed 003 does for spline-heavy parts (mm). Default value: 1e-4.
 */
microEntity: number, 
/**
 * Points of the offsetter closer than this are one point, and an offset piece lying closer
 * to the input than the distance less this is trimmed (mm). Default value: 1e-7.
 */
offset: number, };

/**
 * A tool in the library: a cutter with its cutting data.
 */
export type Tool = { 
/**
 * Tool number (T word, pocket). Default value: 1.
 */
number: number, 
/**
 * Free text for the library and the program's comments. Default value: empty.
 */
name: string, 
/**
 * Spindle speed (rpm), where the tool's speeds are as typed or the stock's material is
 * not set. Default value: 12000.
 */
spindleRpm: number, 
/**
 * Cutting feed (mm/min). Default value: 1000.
 */
feedRate: number, 
/**
 * Feed for vertical entries (mm/min). Default value: 300.
 */
plungeRate: number, 
/**
 * How far the tool stands out of its holder (mm): where the holder's face is, for the
 * verification, the library and the setup sheet.
 * Default value: none.
 */
stickOut: number | null, 
/**
 * Coolant while this tool cuts: off, flood (M8) or mist (M7), as the post writes them.
 * Default value: off.
 */
coolant: Coolant, 
/**
 * Cutting edges (flutes) of a mill; a drill has its two lips. Default value: 2.
 */
flutes: number, 
/**
 * What its edges are made of: `carbide` or `hss`. Default value: carbide.
 */
toolMaterial: ToolMaterial, 
/**
 * Where its speed and feeds come from: `fromMaterial` (the stock's material, where the job
 * names one; [`crate::cutting`]) or `asTyped` (`spindleRpm`, `feedRate`, `plungeRate`).
 * Default value: fromMaterial.
 */
speeds: Speeds, 
/**
 * What holds it (a collet chuck, a router's nut), `stickOut` below its face (the flute
 * length where that is not set): the verification finds it in material. Default value:
 * none.
 */
holder: Holder | null, 
/**
 * What the library it came from gave that swarf does not model, as that library wrote it:
 * each field by format and place (`freecad:parameter.Length`), its value as JSON text
 * (`"\"50.0000 mm\""`). Written back when the tool goes out to the same kind of library,
 * so a round trip keeps what swarf does not use. Default value: none.
 */
libraryFields?: { [key in string]: string }, 
/**
 * End shape. Default value: ball.
 */
shape: Shape, 
/**
 * Cutting diameter (mm). Default value: 6.
 */
diameter: number, 
/**
 * Corner radius of a bull nose (mm), between 0 and half the diameter; ignored for flat and
 * ball cutters. Default value: 1.
 */
cornerRadius: number, 
/**
 * Shank diameter (mm), kept for collision checks. Default value: the cutting diameter.
 */
shankDiameter: number | null, 
/**
 * Length of the fluted part (mm), kept for collision checks. Default value: 20.
 */
fluteLength: number, 
/**
 * Included angle of a drill's point or a V-bit's cone (degrees, more than 0 and less than
 * 180); ignored for the other shapes. Default value: 118 for a drill, 90 for a spot drill
 * and a V-bit.
 */
angle: number | null, 
/**
 * Diameter of a V-bit's or chamfer mill's flat tip (mm, less than the diameter); ignored
 * for the other shapes. Default value: 0.
 */
tipDiameter: number, };

/**
 * What a tool's cutting edges are made of.
 */
export type ToolMaterial = "carbide" | "hss" | "coated";

/**
 * Length unit of a file or of G-code.
 */
export type Units = "mm" | "inch";

/**
 * Which face of the part (as the job places it) a setup holds up, towards the spindle.
 */
export type Up = "+z" | "-z" | "+x" | "-x" | "+y" | "-y";

/**
 * Which axis of the file points up: the part is turned so that it points along +Z (a turn,
 * never a mirror).
 */
export type UpAxis = "z" | "y" | "x" | "-z" | "-y" | "-x";

/**
 * V-carving a drawing's regions.
 */
export type VCarve = { 
/**
 * Default value: "V-carve".
 */
name: string, 
/**
 * Whether the job runs it. Default value: true.
 */
enabled: boolean, 
/**
 * A V-bit (or a spot drill). Default value: 1.
 */
tool: number, 
/**
 * The layers whose loops make the regions. Default value: all.
 */
layers: Array<string>, 
/**
 * The loops to carve, by index as `swarf drawing` lists them (each with the loops inside
 * it as islands). Default value: all on the layers.
 */
loops: Array<number>, 
/**
 * The deepest the V-bit goes (mm); deeper, the region is flat-bottomed at this depth.
 * Default value: none (as deep as the region is wide).
 */
maxDepth: number | null, 
/**
 * A flat end mill that clears the flat floor below `maxDepth`. Default value: none (the
 * V-bit cuts the walls down to the floor; the floor is left with a warning).
 */
flatTool: number | null, 
/**
 * The flat tool's step-over (fraction of its diameter). Default value: 0.4.
 */
stepoverFraction: number, 
/**
 * The flat tool's step-down (mm). Default value: 2.
 */
stepdown: number, 
/**
 * The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
 * and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
 * top).
 */
clearance: number | null, 
/**
 * What `clearance` is measured from. Default value: stockTop.
 */
clearanceFrom: HeightFrom, 
/**
 * The gap above the material where rapid descents stop and the feed begins (mm).
 * Default value: none (the job's, `stock.retract`).
 */
retract: number | null, 
/**
 * The point a clearance `from: point` is measured from: `[x, y, z]` (mm) in the setup's
 * program coordinates. Default value: none.
 */
point: [number, number, number] | null, };

/**
 * A machine vise: two jaws gripping the stock's sides from its bottom up.
 */
export type Vise = { 
/**
 * How far up the stock's sides the jaws reach, from its bottom (mm). Default value: 6.
 */
grip: number, 
/**
 * The jaws' width along the stock's side (mm). Default value: 150.
 */
jawWidth: number, 
/**
 * The jaws' thickness, out from the stock (mm). Default value: 20.
 */
jawThickness: number, 
/**
 * Which way the jaws close: `y` grips the front and back of the stock, `x` its left and
 * right. Default value: y.
 */
closes: ViseAxis, 
/**
 * The least height of material each jaw must grip when its setup starts (mm): a jaw on
 * air or on a thin web is an error naming the setup and the jaw. Default value: half the
 * grip.
 */
leastGrip: number | null, };

/**
 * Which way a vise's jaws close.
 */
export type ViseAxis = "x" | "y";

/**
 * Something the user should know that did not stop the job, with the operation it belongs to
 * (none for the job as a whole: the part, the stock): a warning (something may not be as the
 * user means: look) or a note (for the record). A counted warning says how many places and
 * keeps the first of them, for the page to mark.
 */
export type Warning = { operation: string | null, message: string, level: Level, 
/**
 * How many places it counts (0: it counts none).
 */
count: number, 
/**
 * The first of them (x, y, z in mm, as placed), at most [`Warning::KEPT`].
 */
places: Array<[number, number, number]>, 
/**
 * Loops of the drawing (by index) the operation offers to pick, where it chose what to
 * cut by itself (a V-carve with none picked: the regions it carved), for the user to make
 * the choice their own and change it.
 */
loops: Array<number>, };

/**
 * The work offsets a control has beyond `G54` to `G59`.
 */
export type WorkOffsets = { 
/**
 * `G59.1` to `G59.3` (LinuxCNC, grblHAL). Default value: false.
 */
g59Dot: boolean, 
/**
 * The largest `n` of the extended offsets `G54.1 Pn` (Fanuc's 48), 0 for none. Default
 * value: 0.
 */
extended: number, };

/**
 * The work zero: where the program's origin is on the setup.
 */
export type WorkZero = { 
/**
 * Default value: partTop.
 */
height: ZeroHeight, 
/**
 * Default value: center.
 */
corner: ZeroCorner, 
/**
 * X0 Y0 at this point instead of `corner`: how far it lies from the stock's centre seen
 * from above, in X and Y as the setup holds the part (mm); the page sets it on a hole's
 * centre ([`Job::zero_on`]). Default value: none.
 */
at: [number, number] | null, };

/**
 * Which point of the stock seen from above is X0 Y0.
 */
export type ZeroCorner = "center" | "frontLeft" | "frontRight" | "backLeft" | "backRight";

/**
 * Which height of the setup is Z0 in the program.
 */
export type ZeroHeight = "partTop" | "stockTop" | "stockBottom";

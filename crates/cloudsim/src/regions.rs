//! The region table: with ellipsoids, the packed words whose cells can see a stochastic
//! event, each with its lanes' thresholds as bit planes ([`crate::rng`]), built once per
//! model so that a step compares every draw with its own lane's threshold without
//! a second draw and without rebuilding the planes.
//!
//! Entries are the words of each row from its first to its last word that holds a cell
//! above mask level 0, row after row (rows with no such word have none). Words outside
//! every entry hold no cell above level 0: nothing can happen there and clouds vanish.

use crate::GridSize;
use crate::rng::{
    LANE_PLANES, PLANE_ALWAYS, PLANE_NONZERO, STREAM_ACTIVATION, STREAM_EXTINCTION,
    STREAM_HUMIDITY, THRESHOLD_ONE, UNIFORM_BITS, lane_threshold, lane_threshold_planes,
};

/// The three event streams in the order of [`crate::Model::thresholds`].
pub const STREAMS: [u32; 3] = [STREAM_EXTINCTION, STREAM_HUMIDITY, STREAM_ACTIVATION];

/// Words of the region table's GPU layout per entry: the alive lanes, then
/// [`LANE_PLANES`] planes of each of the three streams (`REGION_ENTRY_WORDS` in WGSL).
pub const REGION_ENTRY_WORDS: usize = 1 + 3 * LANE_PLANES;

/// The [`RegionTable::gpu_layout`] index of a word outside every entry (`NO_REGION` in
/// WGSL).
pub const NO_REGION: u32 = u32::MAX;

/// Entries per group: the CPU reads each plane of 16 consecutive entries at once.
const GROUP: usize = crate::rng::WORD_BATCH;

/// Per-lane threshold planes of the words inside the ellipsoids' rows (see the module
/// documentation).
#[derive(Debug, Clone)]
pub struct RegionTable {
    /// Per row `(y, z)` (index `y + ny z`) its first entry; `rows + 1` values.
    row_start: Vec<u32>,
    /// Packed word index of each entry.
    word: Vec<u32>,
    /// Lanes above mask level 0 of each group of 16 entries (0 past the last entry).
    alive: Vec<[u32; GROUP]>,
    /// Group-major: the planes of the 16 entries of group `g` in the block `g stride ..
    /// (g + 1) stride` (one contiguous read per group), laid out by `layout`. Only the
    /// planes that can be non-zero are stored: every lane's threshold is at most its
    /// stream's base threshold, so the planes above the base's leading one are zero in
    /// every lane (9 of the activation stream's 16 at p = 0.001), and "always" is zero
    /// unless the base is 2^16. This is most of what a step reads from memory.
    planes: Vec<[u32; GROUP]>,
    /// Words of a group's block.
    stride: usize,
    /// Where each stream's planes sit in a block.
    layout: [StreamPlanes; 3],
}

/// The stored planes of one event stream within a group's block.
#[derive(Debug, Clone, Copy)]
struct StreamPlanes {
    /// The "non-zero" plane.
    nonzero: usize,
    /// The "always" plane, when the base threshold is 2^16.
    always: Option<usize>,
    /// The first bit plane that can be non-zero (the base threshold's leading zeros).
    first_plane: usize,
    /// Where bit plane `first_plane` is (the later ones follow).
    offset: usize,
}

impl StreamPlanes {
    /// The block index of plane `k` ([`LANE_PLANES`] numbering), or `None` when the
    /// plane is zero in every lane and not stored.
    #[inline(always)]
    fn index(&self, k: usize) -> Option<usize> {
        match k {
            PLANE_NONZERO => Some(self.nonzero),
            PLANE_ALWAYS => self.always,
            _ if k < self.first_plane => None,
            _ => Some(self.offset + k - self.first_plane),
        }
    }
}

impl RegionTable {
    /// Builds the table from the cells' mask levels (linear index, `0..=256`) and the
    /// three base thresholds `[extinction, humidity, activation]`.
    pub(crate) fn new(size: GridSize, levels: &[u16], thresholds: [u32; 3]) -> Self {
        let nx = size.nx as usize;
        let wpr = size.words_per_row();
        let mut row_start = Vec::with_capacity(size.rows() + 1);
        let mut word = Vec::new();
        let mut alive = Vec::new();
        let mut lane_planes: Vec<[[u32; LANE_PLANES]; 3]> = Vec::new();
        for (row, row_levels) in levels.chunks_exact(nx).enumerate() {
            row_start.push(word.len() as u32);
            let first = row_levels.iter().position(|&l| l > 0);
            let last = row_levels.iter().rposition(|&l| l > 0);
            let (Some(first), Some(last)) = (first, last) else {
                continue;
            };
            for wx in first / 32..=last / 32 {
                let cells = &row_levels[wx * 32..nx.min(wx * 32 + 32)];
                let mut live = 0u32;
                for (lane, &l) in cells.iter().enumerate() {
                    live |= u32::from(l > 0) << lane;
                }
                // lanes past the row's end (the last word's padding) never fire
                let per_stream = |s: usize| {
                    let t: [u32; 32] = std::array::from_fn(|lane| {
                        cells.get(lane).map_or(0, |&l| {
                            lane_threshold(thresholds[s], u32::from(l), STREAMS[s])
                        })
                    });
                    lane_threshold_planes(&t)
                };
                word.push((row * wpr + wx) as u32);
                alive.push(live);
                lane_planes.push(std::array::from_fn(per_stream));
            }
        }
        row_start.push(word.len() as u32);
        let groups = word.len().div_ceil(GROUP);
        let mut grouped_alive = vec![[0u32; GROUP]; groups];
        // the block layout, stream by stream: its non-zero plane, its "always" plane if
        // the base threshold is 2^16, its bit planes from the base's leading one on
        let mut next = 0;
        let layout: [StreamPlanes; 3] = std::array::from_fn(|s| {
            let threshold = thresholds[s];
            // below 2^16, a threshold of b bits has 16 - b leading zero planes
            let first_plane = (threshold.leading_zeros() as usize).saturating_sub(16);
            let mut reserve = |count: usize| {
                next += count;
                next - count
            };
            StreamPlanes {
                nonzero: reserve(1),
                always: (threshold >= THRESHOLD_ONE).then(|| reserve(1)),
                first_plane,
                offset: reserve(UNIFORM_BITS as usize - first_plane),
            }
        });
        let stride = next;
        let mut planes = vec![[0u32; GROUP]; groups * stride];
        for (e, entry) in lane_planes.iter().enumerate() {
            let (g, i) = (e / GROUP, e % GROUP);
            grouped_alive[g][i] = alive[e];
            for (s, stream_planes) in entry.iter().enumerate() {
                for (k, &p) in stream_planes.iter().enumerate() {
                    match layout[s].index(k) {
                        Some(at) => planes[g * stride + at][i] = p,
                        // planes that are not stored are zero in every lane (asserted
                        // by the table's tests through `planes`)
                        None => debug_assert_eq!(p, 0),
                    }
                }
            }
        }
        Self {
            row_start,
            word,
            alive: grouped_alive,
            planes,
            stride,
            layout,
        }
    }

    /// Number of entries.
    pub fn len(&self) -> usize {
        self.word.len()
    }

    /// True when no word holds a cell above level 0 (every ellipsoid lies outside).
    pub fn is_empty(&self) -> bool {
        self.word.is_empty()
    }

    /// The entries of row `row` (index `y + ny z`).
    pub fn row_entries(&self, row: usize) -> std::ops::Range<usize> {
        self.row_start[row] as usize..self.row_start[row + 1] as usize
    }

    /// Packed word index of entry `entry`.
    pub fn word(&self, entry: usize) -> u32 {
        self.word[entry]
    }

    /// Lanes above mask level 0 of entry `entry`.
    pub fn alive(&self, entry: usize) -> u32 {
        self.alive[entry / GROUP][entry % GROUP]
    }

    /// The [`LANE_PLANES`] threshold planes of entry `entry` for stream index `s` (`0`
    /// extinction, `1` humidity, `2` activation).
    pub fn planes(&self, entry: usize, s: usize) -> [u32; LANE_PLANES] {
        let (g, i) = (entry / GROUP, entry % GROUP);
        std::array::from_fn(|k| {
            self.layout[s]
                .index(k)
                .map_or(0, |at| self.planes[g * self.stride + at][i])
        })
    }

    /// Plane `k` of the three streams of the 16 entries of group `group` (entries
    /// `16 group..16 group + 16`, extinction then humidity then activation; entries past
    /// the end read as 0).
    #[inline(always)]
    pub(crate) fn group_plane(&self, group: usize, k: usize) -> [[u32; GROUP]; 3] {
        let block = &self.planes[group * self.stride..(group + 1) * self.stride];
        std::array::from_fn(|s| self.layout[s].index(k).map_or([0; GROUP], |at| block[at]))
    }

    /// Alive lanes of the 16 entries of group `group` (0 past the end).
    #[inline(always)]
    pub(crate) fn group_alive(&self, group: usize) -> [u32; GROUP] {
        self.alive[group]
    }

    /// The GPU layout: per packed word its entry or [`NO_REGION`] (`words` values),
    /// and per entry [`REGION_ENTRY_WORDS`] words (alive lanes, then the planes of
    /// extinction, humidity and activation).
    pub fn gpu_layout(&self, words: usize) -> (Vec<u32>, Vec<u32>) {
        let mut index = vec![NO_REGION; words];
        let mut entries = Vec::with_capacity(self.len().max(1) * REGION_ENTRY_WORDS);
        for (e, &w) in self.word.iter().enumerate() {
            index[w as usize] = e as u32;
            entries.push(self.alive(e));
            for s in 0..3 {
                entries.extend_from_slice(&self.planes(e, s));
            }
        }
        if entries.is_empty() {
            // wgpu storage buffers cannot be empty
            entries.resize(REGION_ENTRY_WORDS, 0);
        }
        (index, entries)
    }
}

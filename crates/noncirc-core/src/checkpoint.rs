//! The checkpoint format: a search state with what it belongs to, checked before a resume.
//!
//! A checkpoint is JSON: a format name and version, the scene (so a resume needs nothing
//! else) and a hash of it, the algorithm and the problem's dimensions, the budget, and the
//! executor's [`SearchState`] with a hash of it. Reading one checks every part against the
//! others, so a damaged or hand-edited file is refused with what is wrong instead of
//! panicking, looping or running a state against another problem; a damage the parts
//! cannot show (a flipped digit in a coordinate) is caught by the state's hash.

use crate::error::{Error, Result};
use crate::problem::SceneProblem;
use crate::scene::{Scene, SearchSpec};
use noncirc_search::{Algorithm, Candidate, SearchState};
use serde::{Deserialize, Serialize};

/// The `format` field of every checkpoint.
pub const FORMAT: &str = "noncirc-checkpoint";
/// The version this build writes and reads; raised whenever the state's layout changes.
/// 2: the state's hash (`state_hash`).
pub(crate) const VERSION: u32 = 2;

/// Members of one island's population on their way to another island of the same
/// problem, with the problem they belong to.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Migrants {
    /// The hash of the problem of the search they come from ([`problem_hash`]).
    pub problem_hash: String,
    pub candidates: Vec<Candidate>,
}

/// A resumable search: everything needed to continue it exactly.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Checkpoint {
    pub format: String,
    pub version: u32,
    /// FNV-1a hash of the scene's JSON, in hex: an edit of the scene is detected.
    pub scene_hash: String,
    pub algorithm: Algorithm,
    /// Free parameters and goals of the scene's search problem.
    pub dim: usize,
    pub goals: usize,
    /// Screening evaluations the search may spend in all.
    pub budget: u64,
    pub scene: Scene,
    pub state: SearchState,
    /// FNV-1a hash of the state's JSON and the budget, in hex, as read or made (`to_json`
    /// writes the state's own): a damaged state is refused.
    pub state_hash: String,
}

impl Checkpoint {
    /// A checkpoint of `state`, a search of `problem` (its scene and dimensions) with
    /// `budget` evaluations.
    pub fn new(problem: &SceneProblem, budget: u64, state: &SearchState) -> Self {
        let scene = problem.base();
        Self {
            format: FORMAT.into(),
            version: VERSION,
            scene_hash: scene_hash(scene),
            algorithm: state.algorithm,
            dim: problem.dim(),
            goals: problem.goals(),
            budget,
            scene: scene.clone(),
            state: state.clone(),
            state_hash: state_hash(state, budget),
        }
    }

    /// The `count` best members of the search's population, for another island of the
    /// same search (an island model, `noncirc.dask.islands`).
    pub fn emigrants(&self, count: usize) -> Migrants {
        Migrants {
            problem_hash: problem_hash(&self.scene),
            candidates: self.state.emigrants(count),
        }
    }

    /// Takes `migrants` in place of the worst members. Migrants from a search of another
    /// problem are refused: their points would mean other parameters, or their fitness
    /// other objectives.
    pub fn immigrate(&mut self, migrants: &Migrants) -> Result<()> {
        let own = problem_hash(&self.scene);
        if migrants.problem_hash != own {
            return Err(state_error(format!(
                "migrants from a search of another problem ({}, not this search's {own}): \
                 islands share the scene and differ only in how they search it",
                migrants.problem_hash
            )));
        }
        self.state
            .immigrate(&migrants.candidates, self.dim, self.goals)
            .map_err(Error::from)
    }

    /// The checkpoint as JSON (non-finite numbers of the state are written as strings),
    /// with the hash of its state as it is now (migrants may have changed it).
    pub fn to_json(&self) -> Vec<u8> {
        let hash = state_hash(&self.state, self.budget);
        let written = if hash == self.state_hash {
            serde_json::to_vec(self)
        } else {
            serde_json::to_vec(&Checkpoint {
                state_hash: hash,
                ..self.clone()
            })
        };
        written.expect("a checkpoint always serialises")
    }

    /// Reads and checks a checkpoint: format and version first (so an old or foreign file
    /// says so), then the whole state against its scene, then the state's hash.
    pub fn from_json(bytes: &[u8]) -> Result<Self> {
        let cp = Self::from_json_unhashed(bytes)?;
        let hash = state_hash(&cp.state, cp.budget);
        if hash != cp.state_hash {
            return Err(state_error(format!(
                "the state's hash is {hash}, the checkpoint says {}: the state or the budget \
                 was damaged or edited (resume from an earlier checkpoint or start again)",
                cp.state_hash
            )));
        }
        Ok(cp)
    }

    /// [`Checkpoint::from_json`] but for the state's hash: every check of the parts against
    /// each other. For the fuzz target, whose mutated states would otherwise never pass the
    /// hash and reach a resumed search.
    #[doc(hidden)]
    pub fn from_json_unhashed(bytes: &[u8]) -> Result<Self> {
        let tree: serde_json::Value =
            serde_json::from_slice(bytes).map_err(|e| state_error(format!("not JSON: {e}")))?;
        match (tree.get("format"), tree.get("version")) {
            (Some(f), Some(v)) if f == FORMAT && v == VERSION => {}
            (Some(f), Some(v)) if f == FORMAT => {
                return Err(state_error(format!(
                    "format version {v}; this noncirc reads version {VERSION}"
                )))
            }
            _ => {
                return Err(state_error(format!(
                    "no '\"format\": \"{FORMAT}\"' with a version: not a noncirc checkpoint, \
                     or one written before checkpoints had a version (start the search again)"
                )))
            }
        }
        let cp: Checkpoint =
            serde_json::from_value(tree).map_err(|e| state_error(format!("damaged: {e}")))?;
        cp.check()?;
        Ok(cp)
    }

    /// Checks the parts against each other.
    fn check(&self) -> Result<()> {
        let hash = scene_hash(&self.scene);
        if hash != self.scene_hash {
            return Err(state_error(format!(
                "the scene's hash is {hash}, the checkpoint says {}: the scene was edited",
                self.scene_hash
            )));
        }
        if self.algorithm != self.state.algorithm {
            return Err(state_error(format!(
                "algorithm '{}' but a '{}' state",
                self.algorithm.name(),
                self.state.algorithm.name()
            )));
        }
        let problem = SceneProblem::new(&self.scene)?;
        if (problem.dim(), problem.goals()) != (self.dim, self.goals) {
            return Err(state_error(format!(
                "{} parameters and {} goals recorded, but the scene's search has {} and {}",
                self.dim,
                self.goals,
                problem.dim(),
                problem.goals()
            )));
        }
        self.state.check(self.dim, self.goals).map_err(Error::from)
    }
}

/// The hash of a scene's search problem: the scene but for how it is searched (the
/// algorithm, population, seed and budget), which islands of one island model may differ
/// in.
pub(crate) fn problem_hash(scene: &Scene) -> String {
    let mut problem = scene.clone();
    let defaults = SearchSpec::default();
    problem.search.algorithm = defaults.algorithm;
    problem.search.population = defaults.population;
    problem.search.seed = defaults.seed;
    problem.search.budget = defaults.budget;
    scene_hash(&problem)
}

/// FNV-1a (64 bits) of the scene's JSON, in hex.
pub(crate) fn scene_hash(scene: &Scene) -> String {
    fnv1a(&serde_json::to_vec(scene).expect("a scene always serialises"))
}

/// FNV-1a (64 bits) of the state's JSON and the budget, in hex.
fn state_hash(state: &SearchState, budget: u64) -> String {
    fnv1a(&serde_json::to_vec(&(state, budget)).expect("a state always serialises"))
}

/// FNV-1a (64 bits) in hex. Written here (a few lines) because it must never change between
/// versions, unlike `std`'s hashers; it detects damage and edits, it does not defend
/// against tampering.
fn fnv1a(bytes: &[u8]) -> String {
    let hash = bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    });
    format!("{hash:016x}")
}

/// A checkpoint that cannot be resumed: what is wrong with it.
fn state_error(problem: String) -> Error {
    Error::Checkpoint(problem)
}

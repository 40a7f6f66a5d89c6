//! The plan: scenes × methods × runs, in a fixed order.

use crate::cell::Cell;
use crate::error::SuiteError;
use crate::method::{Method, standard_methods};
use crate::scene::{SuiteScene, standard_scenes};

/// What the suite runs.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The scenes.
    pub scenes: Vec<SuiteScene>,
    /// The methods.
    pub methods: Vec<Method>,
    /// Runs of each method on each scene (K).
    pub runs: u32,
}

impl Plan {
    /// The standard scenes and methods, `runs` times each.
    pub fn standard(runs: u32) -> Result<Self, SuiteError> {
        Self::new(standard_scenes(), standard_methods(), runs)
    }

    /// A plan, refused when it has no scene, no method or no run.
    pub fn new(
        scenes: Vec<SuiteScene>,
        methods: Vec<Method>,
        runs: u32,
    ) -> Result<Self, SuiteError> {
        if scenes.is_empty() {
            return Err(SuiteError::EmptyPlan("no scene"));
        }
        if methods.is_empty() {
            return Err(SuiteError::EmptyPlan("no method"));
        }
        if runs == 0 {
            return Err(SuiteError::EmptyPlan("no run (K must be at least 1)"));
        }
        Ok(Self {
            scenes,
            methods,
            runs,
        })
    }

    /// Keeps only the scenes named in `names` (all when empty), in the plan's order.
    pub fn only_scenes(mut self, names: &[String]) -> Result<Self, SuiteError> {
        let known: Vec<String> = self.scenes.iter().map(|s| s.name.clone()).collect();
        check_names("scene", names, &known)?;
        if !names.is_empty() {
            self.scenes.retain(|s| names.contains(&s.name));
        }
        Ok(self)
    }

    /// Keeps only the methods named in `names` (all when empty), in the plan's order.
    pub fn only_methods(mut self, names: &[String]) -> Result<Self, SuiteError> {
        let known: Vec<String> = self.methods.iter().map(|m| m.name.clone()).collect();
        check_names("method", names, &known)?;
        if !names.is_empty() {
            self.methods.retain(|m| names.contains(&m.name));
        }
        Ok(self)
    }

    /// Every cell, run by run (all of run 0 first, so that a partial suite already covers
    /// every scene and method once), then scene by scene, then method by method.
    pub fn cells(&self) -> Vec<Cell> {
        let mut cells = Vec::new();
        for run in 0..self.runs {
            for scene in &self.scenes {
                for method in &self.methods {
                    cells.push(Cell {
                        scene: scene.name.clone(),
                        method: method.name.clone(),
                        run,
                    });
                }
            }
        }
        cells
    }

    /// The scene named `name`.
    pub fn scene(&self, name: &str) -> Option<&SuiteScene> {
        self.scenes.iter().find(|s| s.name == name)
    }

    /// The method named `name`.
    pub fn method(&self, name: &str) -> Option<&Method> {
        self.methods.iter().find(|m| m.name == name)
    }
}

fn check_names(kind: &'static str, names: &[String], known: &[String]) -> Result<(), SuiteError> {
    match names.iter().find(|n| !known.contains(n)) {
        Some(name) => Err(SuiteError::Unknown {
            kind,
            name: name.clone(),
            known: known.join(", "),
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_go_run_by_run() {
        let plan = Plan::standard(3).unwrap();
        let cells = plan.cells();
        assert_eq!(cells.len(), 6 * plan.methods.len() * 3);
        let first_of_run_1 = 6 * plan.methods.len();
        assert!(cells[..first_of_run_1].iter().all(|c| c.run == 0));
        assert_eq!(cells[first_of_run_1].run, 1);
    }

    #[test]
    fn filters_refuse_unknown_names() {
        let plan = Plan::standard(1).unwrap();
        let err = plan
            .clone()
            .only_scenes(&["atrium".to_string()])
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("unknown scene `atrium`") && err.contains("corridor"),
            "{err}"
        );
        let only = plan.only_methods(&["refresh".to_string()]).unwrap();
        assert_eq!(only.methods.len(), 1);
    }

    #[test]
    fn an_empty_plan_is_refused() {
        assert!(Plan::standard(0).is_err());
        assert!(Plan::new(vec![], standard_methods(), 1).is_err());
    }
}

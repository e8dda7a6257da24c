"""The recipes: one base + per-task / per-method / ablation overrides, merged as LightningCLI merges configs."""

from __future__ import annotations

import pytest
import yaml

from radaraug import recipes
from radaraug.errors import ConfigError
from radaraug.testsets.tasks import TASKS
from radaraug.training.methods import METHODS


def test_one_name_per_task_and_method_from_the_override_files():
    assert set(recipes.tasks()) == set(TASKS) and set(recipes.methods()) == set(METHODS)
    assert set(recipes.recipe_names()) == {f"{t}_{m}" for t in TASKS for m in METHODS}


@pytest.mark.parametrize("name", recipes.recipe_names())
def test_a_name_is_base_task_and_method_merged(name):
    files = recipes.recipe_files(name)
    assert [p.relative_to(recipes.RECIPES_DIR).parts[0] for p in files] == ["base.yaml", "task", "method"]
    cfg = recipes.compose(name)
    task, method = files[1].stem, files[2].stem
    assert name == f"{task}_{method}"
    assert cfg["data"]["task"] == task and recipes.method_of(cfg["data"]["method"]) == method
    # twin randomization on by default, its catalog without the persistent effects (spur, fan)
    assert cfg["data"]["twin"]["randomization"] == {"catalog": {"spur_tone": {"probability": 0.0},
                                                        "vibrating_clutter": {"probability": 0.0}}}
    # the base's keys are all there, the method's added: nothing of the base lost in the merge
    base = yaml.safe_load((recipes.RECIPES_DIR / "base.yaml").read_text())
    for section in ("trainer", "model", "data"):
        assert set(base[section]) <= set(cfg[section])
    # the printed recipe is the merged one (a copy to edit)
    assert yaml.safe_load(recipes.recipe_text(name)) == cfg


def test_the_overrides_are_small():
    # one place for each hyperparameter: an override holds only what its task / method / ablation changes
    for kind, most in (("task", 1), ("method", 5), ("ablation", 3)):
        for p in (recipes.RECIPES_DIR / kind).glob("*.yaml"):
            data = yaml.safe_load(p.read_text())
            assert set(data) == {"data"} and len(data["data"]) <= most, p.name


def test_merge_is_key_by_key_for_mappings_and_replaces_the_rest():
    base = {"data": {"a": 1, "r": True, "l": [1, 2]}, "model": {"lr": 1}}
    out = recipes.merge(base, {"data": {"r": {"x": 1}, "l": [3]}})
    assert out == {"data": {"a": 1, "r": {"x": 1}, "l": [3]}, "model": {"lr": 1}}
    assert base["data"]["r"] is True  # the inputs are not changed
    # another class: its own arguments, not the old class's
    cdr = {"method": {"class_path": "m.CDR", "init_args": {"floor": "normal"}}}
    assert recipes.merge(cdr, {"method": {"class_path": "m.RT"}}) == {"method": {"class_path": "m.RT"}}
    assert recipes.merge(cdr, {"method": {"init_args": {"test_dr": True}}})["method"]["init_args"] == {
        "floor": "normal", "test_dr": True}


@pytest.mark.parametrize("name", recipes.ablations())
def test_every_ablation_names_its_method_and_changes_something(name):
    method = recipes.ablation_method(name)
    assert method in METHODS and name.startswith(method.split("_")[0])
    main = recipes.compose(f"occupancy_{method}")
    changed = recipes.compose(f"occupancy_{method}", f"ablation/{name}")
    assert changed != main and recipes.method_of(changed["data"]["method"]) == method


def test_names_of_the_old_checkout_place_and_single_files_resolve():
    assert recipes.recipe_files("recipes/counting_cdr.yaml") == recipes.recipe_files("counting_cdr")
    assert recipes.recipe_files("ablation/rt_paper_image")[0].name == "rt_paper_image.yaml"
    assert recipes.is_recipe_name("base") and not recipes.is_recipe_name("my.yaml")


def test_an_unknown_name_is_one_error_listing_the_recipes():
    with pytest.raises(ConfigError, match="occupancy_randomdr"):
        recipes.recipe_files("occupancy_magic")


def test_a_bad_recipe_file_is_named(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("- a list\n")
    with pytest.raises(ConfigError, match="bad.yaml"):
        recipes.compose(str(bad))
    bad.write_text("data: [\n")
    with pytest.raises(ConfigError, match="bad.yaml"):
        recipes.compose(str(bad))

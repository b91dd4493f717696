"""The iisy models agree with the published data and with their own geometry."""

import numpy as np
import pytest
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
from pydrake.multibody.tree import CalcSpatialInertia, SpatialInertia
from pydrake.systems.framework import DiagramBuilder

from hrc_drake.iisy import (
    BASE_FRAME,
    FLANGE_FRAME,
    JOINT_NAMES,
    LINK_NAMES,
    TCP_FRAME,
    VARIANTS,
    add_iisy,
    add_tool,
)


class Station:
    """One welded iisy (optionally with the tool) in a plant with a SceneGraph."""

    def __init__(self, variant_name: str, with_tool: bool = False):
        builder = DiagramBuilder()
        self.plant, self.scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=0.001)
        parser = Parser(self.plant)
        self.robot = add_iisy(self.plant, variant_name, parser)
        self.plant.WeldFrames(
            self.plant.world_frame(), self.plant.GetFrameByName(BASE_FRAME, self.robot)
        )
        if with_tool:
            add_tool(self.plant, self.robot, parser)
        self.plant.Finalize()
        self.diagram = builder.Build()
        self.context = self.diagram.CreateDefaultContext()
        self.plant_context = self.plant.GetMyContextFromRoot(self.context)

    def frame_in_world(self, name: str):
        return self.plant.GetFrameByName(name).CalcPoseInWorld(self.plant_context)

    def contacts(self, q) -> list[tuple[str, str]]:
        self.plant.SetPositions(self.plant_context, self.robot, q)
        query = self.scene_graph.get_query_output_port().Eval(
            self.scene_graph.GetMyContextFromRoot(self.context)
        )
        inspector = query.inspector()
        return [
            (inspector.GetName(pair.id_A), inspector.GetName(pair.id_B))
            for pair in query.ComputePointPairPenetration()
        ]


@pytest.fixture(scope="module", params=sorted(VARIANTS))
def station(request) -> tuple[Station, object]:
    return Station(request.param), VARIANTS[request.param]


def test_zero_pose_puts_flange_at_nominal_reach(station):
    station, variant = station
    p_WF = station.frame_in_world(FLANGE_FRAME).translation()
    assert np.hypot(p_WF[0], p_WF[1]) == pytest.approx(variant.reach, abs=1e-3)


def test_flange_z_points_away_from_wrist_at_zero_pose(station):
    station, _ = station
    z_WF = station.frame_in_world(FLANGE_FRAME).rotation().matrix()[:, 2]
    np.testing.assert_allclose(z_WF, [1.0, 0.0, 0.0], atol=1e-9)


def test_names_follow_kuka(station):
    station, variant = station
    plant, robot = station.plant, station.robot
    assert [plant.get_body(i).name() for i in plant.GetBodyIndices(robot)] == list(LINK_NAMES)
    assert [plant.get_joint(i).name() for i in plant.GetJointIndices(robot)][:6] == list(
        JOINT_NAMES
    )
    assert variant.joint_names == JOINT_NAMES


def test_joint_limits_are_the_published_ones(station):
    station, variant = station
    plant = station.plant
    checks = {
        "position_lower": plant.GetPositionLowerLimits(),
        "position_upper": plant.GetPositionUpperLimits(),
        "velocity_limits": plant.GetVelocityUpperLimits(),
        "acceleration_limits": plant.GetAccelerationUpperLimits(),
        "effort_limits": plant.GetEffortUpperLimits(),
    }
    for field, parsed in checks.items():
        np.testing.assert_allclose(parsed, getattr(variant, field), rtol=1e-8, err_msg=field)
    np.testing.assert_allclose(
        plant.GetVelocityLowerLimits(), -np.array(variant.velocity_limits), rtol=1e-8
    )


def test_published_limits_spot_check():
    """A few numbers straight from the facts page, against unit mix-ups in iisy.py."""
    r760, r1300 = VARIANTS["lbr_iisy3_r760"], VARIANTS["lbr_iisy11_r1300"]
    assert np.degrees(r760.position_lower[1]) == pytest.approx(-230.0)
    assert np.degrees(r760.position_upper[3]) == pytest.approx(175.0)
    assert np.degrees(r1300.position_upper[3]) == pytest.approx(180.0)
    assert np.degrees(r1300.velocity_limits[5]) == pytest.approx(430.0)
    assert r1300.acceleration_limits[1] == pytest.approx(1.11)


def test_total_mass_is_published(station):
    station, variant = station
    plant = station.plant
    mass = sum(plant.get_body(i).default_mass() for i in plant.GetBodyIndices(station.robot))
    assert mass == pytest.approx(variant.total_mass, rel=0.01)


def geometry_inertia(station: Station, body) -> SpatialInertia:
    """Unit-density spatial inertia of a body's collision shapes, about its origin."""
    inspector = station.scene_graph.model_inspector()
    total = SpatialInertia.Zero()
    for geometry_id in station.plant.GetCollisionGeometriesForBody(body):
        X_BG = inspector.GetPoseInFrame(geometry_id)
        M_GGo_G = CalcSpatialInertia(inspector.GetShape(geometry_id), 1.0)
        total += M_GGo_G.ReExpress(X_BG.rotation()).Shift(-X_BG.translation())
    return total


def test_link_inertias_are_valid_and_match_geometry(station):
    station, _ = station
    plant = station.plant
    for index in plant.GetBodyIndices(station.robot):
        body = plant.get_body(index)
        M_BBo_B = body.default_spatial_inertia()
        assert M_BBo_B.IsPhysicallyValid(), body.name()
        moments = M_BBo_B.CalcRotationalInertia().CalcPrincipalMomentsOfInertia()
        assert moments[0] + moments[1] >= moments[2] * (1 - 1e-9), body.name()
        from_geometry = geometry_inertia(station, body)
        scale = M_BBo_B.get_mass() / from_geometry.get_mass()
        np.testing.assert_allclose(
            M_BBo_B.CopyToFullMatrix6(),
            from_geometry.CopyToFullMatrix6() * scale,
            rtol=1e-6,
            atol=1e-8,
            err_msg=body.name(),
        )


def test_home_is_within_limits_and_free_of_self_contact(station):
    station, variant = station
    home = np.array(variant.home)
    assert np.all(home >= variant.position_lower) and np.all(home <= variant.position_upper)
    assert station.contacts(np.zeros(6)) == []
    assert station.contacts(home) == []


@pytest.mark.parametrize("variant_name", sorted(VARIANTS))
def test_tool_tcp_points_down_at_home(variant_name):
    station = Station(variant_name, with_tool=True)
    assert station.contacts(VARIANTS[variant_name].home) == []
    X_WT = station.frame_in_world(TCP_FRAME)
    np.testing.assert_allclose(X_WT.rotation().matrix()[:, 2], [0.0, 0.0, -1.0], atol=1e-9)
    assert X_WT.translation()[2] > 0.05

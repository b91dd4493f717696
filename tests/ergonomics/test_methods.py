"""RULA, REBA and the NIOSH lifting equation against published worked examples and table
cells (docs/ergonomics.md names every source). The expected values are the publications',
never numbers the code produced."""

import pytest

from hrc_drake.ergonomics import niosh, reba, rula


def test_rula_cardboard_factory_example_scores_grand_score_3():
    """'Ejercicio resuelto Método RULA' (cardboard factory; the ergonautas/INSHT teaching
    material): shoulder flexed 20-45 deg (2), elbow under 60 deg (2), wrist neutral (1),
    mid-range twist (1): Table A 3. Neck, trunk and legs neutral: Table B 1. One 250 g
    piece every 10 s: muscle use +1 on both sides, force 0. C = 4, D = 2, grand score 3,
    action level 2."""
    parts = rula.RulaParts(
        upper_arm=rula.upper_arm_score(40),
        lower_arm=rula.lower_arm_score(45),
        wrist=rula.wrist_score(0),
        wrist_twist=rula.wrist_twist_score(),
        neck=rula.neck_score(5),
        trunk=rula.trunk_score(0),
        legs=rula.legs_score(True),
        muscle_use_a=rula.muscle_use_score(static=False, repeated=True),
        force_a=rula.force_score(0.25),
        muscle_use_b=rula.muscle_use_score(static=False, repeated=True),
        force_b=rula.force_score(0.25),
    )
    assert (parts.upper_arm, parts.lower_arm, parts.wrist, parts.wrist_twist) == (2, 2, 1, 1)
    assert rula.posture_score_a(2, 2, 1, 1) == 3
    assert rula.posture_score_b(1, 1, 1) == 1
    assert rula.grand_score(parts) == 3
    assert rula.action_level(3) == 2


@pytest.mark.parametrize(
    "upper_arm, lower_arm, wrist, twist, expected",
    [  # McAtamney & Corlett 1993, Table 1 (Table A), as the paper prints it
        (1, 1, 1, 1, 1),
        (1, 3, 1, 2, 3),
        (2, 1, 3, 1, 3),
        (3, 1, 1, 2, 3),
        (3, 2, 1, 2, 4),
        (4, 3, 2, 2, 5),
        (5, 2, 3, 1, 6),
        (5, 2, 3, 2, 7),
        (5, 3, 4, 2, 8),
        (6, 1, 4, 2, 9),
        (6, 3, 1, 1, 9),
    ],
)
def test_rula_table_a_cells(upper_arm, lower_arm, wrist, twist, expected):
    assert rula.posture_score_a(upper_arm, lower_arm, wrist, twist) == expected


@pytest.mark.parametrize(
    "neck, trunk, legs, expected",
    [(1, 1, 2, 3), (1, 2, 1, 2), (3, 4, 2, 6), (4, 2, 2, 6), (6, 4, 2, 9), (2, 3, 1, 4)],
)
def test_rula_table_b_cells(neck, trunk, legs, expected):
    """McAtamney & Corlett 1993, Table 2 (Table B)."""
    assert rula.posture_score_b(neck, trunk, legs) == expected


@pytest.mark.parametrize(
    "c, d, expected", [(1, 1, 1), (3, 7, 6), (4, 5, 5), (5, 4, 5), (8, 1, 5), (9, 9, 7)]
)
def test_rula_table_c_cells_cap_at_8_and_7(c, d, expected):
    """Table 3 (grand score); scores C of 8 and more share a row, D of 7 and more a column."""
    parts = rula.RulaParts(1, 1, 1, 1, 1, 1, 1, muscle_use_a=c - 1, muscle_use_b=d - 1)
    assert rula.grand_score(parts) == expected


def test_rula_force_and_muscle_use_bands():
    """The paper's stage 2: under 2 kg intermittent 0; 2-10 kg intermittent 1, static or
    repeated 2; over 10 kg intermittent 2, static or repeated 3; shocks 3."""
    assert [rula.force_score(m) for m in (1.9, 2.0, 10.0, 10.1)] == [0, 1, 1, 2]
    assert [rula.force_score(m, True) for m in (5.0, 12.0)] == [2, 3]
    assert rula.force_score(0.5, shock=True) == 3
    assert rula.muscle_use_score(static=True, repeated=False) == 1


def test_reba_worker_handling_a_load_example_scores_4():
    """'Método REBA - ejemplos prácticos', example 1 (a worker handling a load), with the
    tables of INSHT NTP 601: neck 0-20 deg (1); bilateral, knees 30-60 deg (2); trunk about
    20 deg (2): Table A 3, load over 10 kg +2, score A 5. Lower arm 60-100 (1), wrist about
    0 (1), upper arm about 20 deg and abducted (2): Table B 1. Table C: 4, medium risk."""
    parts = reba.RebaParts(
        trunk=reba.trunk_score(20),
        neck=reba.neck_score(10),
        legs=reba.legs_score(True, 40),
        upper_arm=reba.upper_arm_score(20, abducted_or_rotated=True),
        lower_arm=reba.lower_arm_score(80),
        wrist=reba.wrist_score(0),
        load=reba.load_score(12.0),
    )
    assert (parts.trunk, parts.neck, parts.legs) == (2, 1, 2)
    assert (parts.upper_arm, parts.lower_arm, parts.wrist, parts.load) == (2, 1, 1, 2)
    assert reba.score_a(2, 1, 2) == 3
    assert reba.score_b(2, 1, 1) == 1
    assert reba.reba_score(parts) == 4
    assert reba.risk_level(4) == "medium"


@pytest.mark.parametrize(
    "trunk, neck, legs, expected",
    [  # Hignett & McAtamney 2000, Table A (as the REBA worksheet and NTP 601 print it)
        (1, 1, 1, 1),
        (1, 3, 1, 3),
        (1, 3, 4, 6),
        (3, 1, 1, 2),
        (3, 2, 2, 5),
        (4, 3, 3, 8),
        (5, 1, 4, 8),
        (5, 3, 4, 9),
    ],
)
def test_reba_table_a_cells(trunk, neck, legs, expected):
    assert reba.score_a(trunk, neck, legs) == expected


@pytest.mark.parametrize(
    "upper_arm, lower_arm, wrist, expected",
    [(1, 1, 3, 2), (1, 2, 3, 3), (3, 2, 3, 5), (4, 2, 3, 7), (5, 1, 3, 8), (6, 2, 1, 8)],
)
def test_reba_table_b_cells(upper_arm, lower_arm, wrist, expected):
    """Hignett & McAtamney 2000, Table B."""
    assert reba.score_b(upper_arm, lower_arm, wrist) == expected


@pytest.mark.parametrize(
    "a, b, expected",
    [(1, 1, 1), (1, 12, 7), (2, 12, 8), (6, 9, 10), (8, 5, 10), (9, 10, 12), (12, 1, 12)],
)
def test_reba_table_c_cells(a, b, expected):
    """Hignett & McAtamney 2000, Table C (score A rows, score B columns)."""
    assert reba.TABLE_C[a - 1][b - 1] == expected


def test_reba_bands_and_risk_levels():
    """Trunk upright 1, 0-20 deg either way 2, 20-60 flexion or over 20 extension 3, over
    60 flexion 4; load under 5 kg 0, 5-10 kg 1, over 10 kg 2, +1 for a shock; risk levels
    negligible 1, low 2-3, medium 4-7, high 8-10, very high 11-15."""
    assert [reba.trunk_score(a) for a in (0, 15, -15, 45, -25, 70)] == [1, 2, 2, 3, 3, 4]
    assert [reba.load_score(m) for m in (4.9, 5.0, 10.0, 10.5)] == [0, 1, 1, 2]
    assert reba.load_score(1.0, shock=True) == 1
    assert [reba.risk_level(s) for s in (1, 3, 7, 10, 11)] == [
        "negligible",
        "low",
        "medium",
        "high",
        "very high",
    ]


def test_niosh_dish_washing_example_rwl_and_lifting_index():
    """NIOSH Applications Manual (1994), example 2, dish-washing machine unloading: 20 lb
    trays, H 20 in, V 44 in at the origin and 7 in at the destination, A 30 deg at both,
    5 lifts/min for under an hour, good coupling. The manual gives FM 0.80 and RWL 14.4 lb
    at the origin, 13.3 lb at the destination, LI 1.4 and 1.5 (it rounds each multiplier to
    two decimals, hence the 1 % tolerance)."""
    origin, destination = niosh.LiftPoint(20, 44, 30), niosh.LiftPoint(20, 7, 30)
    distance = 44 - 7
    results = []
    for point in (origin, destination):
        factors = niosh.multipliers(point, distance, 5, niosh.SHORT, "good", niosh.US)
        assert factors.fm == pytest.approx(0.80)
        assert factors.hm == pytest.approx(0.50)
        assert factors.am == pytest.approx(0.90, abs=0.005)
        assert factors.dm == pytest.approx(0.87, abs=0.005)
        results.append(niosh.recommended_weight_limit(factors, niosh.US))
    assert results[0] == pytest.approx(14.4, rel=0.01)
    assert results[1] == pytest.approx(13.3, rel=0.01)
    assert niosh.lifting_index(20, results[0]) == pytest.approx(1.4, abs=0.05)
    assert niosh.lifting_index(20, results[1]) == pytest.approx(1.5, abs=0.05)


@pytest.mark.parametrize(
    "frequency, duration, v, expected",
    [  # Applications Manual, Table 5 (V in inches)
        (0.1, niosh.SHORT, 20, 1.00),
        (1, niosh.LONG, 40, 0.75),
        (4, niosh.MODERATE, 20, 0.72),
        (9, niosh.LONG, 20, 0.00),
        (9, niosh.LONG, 40, 0.15),
        (12, niosh.MODERATE, 40, 0.21),
        (15, niosh.SHORT, 40, 0.28),
        (16, niosh.SHORT, 40, 0.00),
    ],
)
def test_niosh_frequency_multiplier_table(frequency, duration, v, expected):
    assert niosh.frequency_multiplier(frequency, duration, v, niosh.US) == expected


def test_niosh_coupling_multiplier_and_range_rules():
    """Table 7 (fair: 0.95 below V 30 in, 1.00 above; poor 0.90) and the manual's rules:
    H below 10 in counts as 10 in, beyond 25 in HM 0; V beyond 70 in VM 0; D below 10 in
    counts as 10 in, beyond 70 in DM 0; A beyond 135 deg AM 0."""
    assert niosh.coupling_multiplier("fair", 20, niosh.US) == 0.95
    assert niosh.coupling_multiplier("fair", 40, niosh.US) == 1.00
    assert niosh.coupling_multiplier("poor", 40, niosh.US) == 0.90
    assert niosh.horizontal_multiplier(5, niosh.US) == 1.0
    assert niosh.horizontal_multiplier(26, niosh.US) == 0.0
    assert niosh.vertical_multiplier(71, niosh.US) == 0.0
    assert niosh.distance_multiplier(5, niosh.US) == pytest.approx(1.0)
    assert niosh.distance_multiplier(71, niosh.US) == 0.0
    assert niosh.asymmetry_multiplier(136) == 0.0
    assert niosh.lifting_index(10, 0.0) == float("inf")
    assert niosh.out_of_range(niosh.LiftPoint(70, 80, 0), 30, 2)  # H beyond 63 cm


def test_niosh_metric_constants():
    """Waters et al. 1993, metric form: LC 23 kg, HM 25/H, VM 1 - 0.003|V - 75|,
    DM 0.82 + 4.5/D (cm). The ideal lift (H 25, V 75, D 25 cm, symmetric, occasional,
    good coupling) is recommended the load constant."""
    factors = niosh.multipliers(niosh.LiftPoint(25, 75, 0), 25, 0.2, niosh.SHORT, "good")
    assert niosh.recommended_weight_limit(factors) == pytest.approx(23.0)

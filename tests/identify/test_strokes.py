"""Strokes of a time series (:mod:`breakaway.identify.strokes`), on hand-made paths."""

import numpy as np

from breakaway.identify.strokes import (ONE_PLACE_SHARE, breakaway_places,
                                        breakaways_apart, last_reversal)


def test_each_row_knows_the_sample_before_its_last_reversal():
    d = np.array([1, 1, 1, -1, -1, 1, 1])
    last, reversed_ = last_reversal(d)
    np.testing.assert_array_equal(last, [0, 0, 0, 2, 2, 4, 4])
    np.testing.assert_array_equal(reversed_, [False, False, False, True, True, True, True])


def test_a_stroke_breaks_away_where_it_turned_once_it_reaches_gross_sliding():
    # out 0 -> 4, back 4 -> 1, out again 1 -> 3; the middle stroke never slides
    x = np.array([0, 1, 2, 3, 4, 3, 2, 1, 2, 3], dtype=float)
    d = np.sign(np.diff(x, prepend=-1.0))
    d[0] = 1.0
    z = np.abs(x - x[last_reversal(d)[0]])
    positive, negative = breakaway_places(x, d, z, sliding_z=1.5)
    # the first stroke has no reversal before it; the back stroke reaches z = 3 from
    # x = 4; the last reaches z = 2 from x = 1
    np.testing.assert_array_equal(positive, [1.0])
    np.testing.assert_array_equal(negative, [4.0])
    # with a higher threshold the last stroke no longer slides
    positive, negative = breakaway_places(x, d, z, sliding_z=2.5)
    assert positive.size == 0 and negative.tolist() == [4.0]


def test_places_are_apart_only_within_a_share_of_the_distance_between_directions():
    distance = 10.0
    # places spread evenly about each direction's median: a spread just inside and just
    # outside the share of the distance between the medians
    inside = ONE_PLACE_SHARE * distance * 0.99 / 2
    outside = ONE_PLACE_SHARE * distance * 1.01 / 2
    assert breakaways_apart([-inside, 0.0, inside], [distance] * 3)
    assert not breakaways_apart([-outside, 0.0, outside], [distance] * 3)
    assert not breakaways_apart([0.0] * 3, [distance - outside, distance, distance + outside])
    # a direction that never breaks away cannot show a dependence within it
    assert breakaways_apart([], [1.0, 2.0])

"""Shared fixtures of the Python tests: the thesis's asperity-scale cases (Tables 3.1-3.4)."""
import pytest

import asperity
from asperity import thesis


@pytest.fixture
def micro_pair() -> asperity.ContactPair:
    return thesis.micro_pair()


@pytest.fixture
def micro_params() -> asperity.FrictionParameters:
    return thesis.micro_params()


@pytest.fixture
def nano_pair() -> asperity.ContactPair:
    return thesis.nano_pair()

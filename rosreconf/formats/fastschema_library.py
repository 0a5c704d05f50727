"""The verdict of component-library.schema.json as code: written by
scripts/fast_validators.py, do not edit (see structure.fast_validator).
"""

# ruff: noqa
# fmt: off
# mypy: ignore-errors
SOURCE = '0dad6991a890718e842e08b35603016a4d5881691e110b571dd57feedea646e9'
import re

_NUMBER = (int, float)
_MISSING = object()
_C0 = frozenset({'components', 'description', 'format', 'name', 'version'})
_C1 = re.compile('^[A-Za-z][A-Za-z0-9_]*$').search
_C2 = set()  # texts _C1 matched
_C3 = frozenset({'abstraction', 'description', 'dynamics', 'excludes', 'failure_probability', 'metrics', 'name', 'needs', 'provides', 'requires', 'ros', 'schemas'})
_C4 = frozenset({'action', 'qos', 'service', 'topic', 'type'})
_C5 = re.compile('^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*$').search
_C6 = set()  # texts _C5 matched
_C7 = re.compile('^[A-Za-z][A-Za-z0-9_]*/((msg|srv|action)/)?[A-Za-z][A-Za-z0-9_]*$').search
_C8 = set()  # texts _C7 matched
_C9 = frozenset({'deadline', 'depth', 'durability', 'lease_duration', 'liveliness', 'reliability'})
_C10 = frozenset({'best_effort', 'reliable'})
_C11 = frozenset({'transient_local', 'volatile'})
_C12 = frozenset({'automatic', 'manual_by_topic'})
_C13 = frozenset({'any_of'})
_C14 = frozenset({'args', 'executable', 'lifecycle', 'namespace', 'node', 'package', 'parameters', 'remappings'})
_C15 = re.compile('^[A-Za-z0-9_.\\-]+$').search
_C16 = set()  # texts _C15 matched
_C17 = frozenset({'substitution'})
_C18 = frozenset({'delay', 'state_space', 'transfer_function'})
_C19 = frozenset({'den', 'num'})
_C20 = frozenset({'A', 'B', 'C', 'D'})


def _branch0(data):
    if not type(data) is dict:
        return False
    if ((not ('topic' not in data)) + (not ('service' not in data)) + (not ('action' not in data))) != 1:
        return False
    if not data.keys() <= _C4:
        return False
    v36 = data.get('topic', _MISSING)
    if v36 is not _MISSING:
        if not type(v36) is str:
            return False
        if v36 not in _C6:
            if _C5(v36) is None:
                return False
            if len(_C6) < 100000:
                _C6.add(v36)
    v37 = data.get('service', _MISSING)
    if v37 is not _MISSING:
        if not type(v37) is str:
            return False
        if v37 not in _C6:
            if _C5(v37) is None:
                return False
            if len(_C6) < 100000:
                _C6.add(v37)
    v38 = data.get('action', _MISSING)
    if v38 is not _MISSING:
        if not type(v38) is str:
            return False
        if v38 not in _C6:
            if _C5(v38) is None:
                return False
            if len(_C6) < 100000:
                _C6.add(v38)
    v39 = data.get('type', _MISSING)
    if v39 is _MISSING:
        return False
    if not type(v39) is str:
        return False
    if v39 not in _C8:
        if _C7(v39) is None:
            return False
        if len(_C8) < 100000:
            _C8.add(v39)
    v40 = data.get('qos', _MISSING)
    if v40 is not _MISSING:
        if not type(v40) is dict:
            return False
        if not v40.keys() <= _C9:
            return False
        v41 = v40.get('reliability', _MISSING)
        if v41 is not _MISSING:
            if not (type(v41) is str and v41 in _C10):
                return False
        v42 = v40.get('durability', _MISSING)
        if v42 is not _MISSING:
            if not (type(v42) is str and v42 in _C11):
                return False
        v43 = v40.get('deadline', _MISSING)
        if v43 is not _MISSING:
            if not (type(v43) in _NUMBER or v43 is None):
                return False
            if type(v43) in _NUMBER and v43 <= 0:
                return False
        v44 = v40.get('liveliness', _MISSING)
        if v44 is not _MISSING:
            if not (type(v44) is str and v44 in _C12):
                return False
        v45 = v40.get('lease_duration', _MISSING)
        if v45 is not _MISSING:
            if not (type(v45) in _NUMBER or v45 is None):
                return False
            if type(v45) in _NUMBER and v45 <= 0:
                return False
        v46 = v40.get('depth', _MISSING)
        if v46 is not _MISSING:
            if not (type(v46) is int or (type(v46) is float and v46.is_integer())):
                return False
            if v46 < 0:
                return False
    return True


def _branch1(data):
    if not type(data) is dict:
        return False
    if not data.keys() <= _C13:
        return False
    v60 = data.get('any_of', _MISSING)
    if v60 is _MISSING:
        return False
    if not type(v60) is list:
        return False
    if len(v60) < 2:
        return False
    for v61 in v60:
        if not type(v61) is dict:
            return False
        if ((not ('topic' not in v61)) + (not ('service' not in v61)) + (not ('action' not in v61))) != 1:
            return False
        if not v61.keys() <= _C4:
            return False
        v62 = v61.get('topic', _MISSING)
        if v62 is not _MISSING:
            if not type(v62) is str:
                return False
            if v62 not in _C6:
                if _C5(v62) is None:
                    return False
                if len(_C6) < 100000:
                    _C6.add(v62)
        v63 = v61.get('service', _MISSING)
        if v63 is not _MISSING:
            if not type(v63) is str:
                return False
            if v63 not in _C6:
                if _C5(v63) is None:
                    return False
                if len(_C6) < 100000:
                    _C6.add(v63)
        v64 = v61.get('action', _MISSING)
        if v64 is not _MISSING:
            if not type(v64) is str:
                return False
            if v64 not in _C6:
                if _C5(v64) is None:
                    return False
                if len(_C6) < 100000:
                    _C6.add(v64)
        v65 = v61.get('type', _MISSING)
        if v65 is _MISSING:
            return False
        if not type(v65) is str:
            return False
        if v65 not in _C8:
            if _C7(v65) is None:
                return False
            if len(_C8) < 100000:
                _C8.add(v65)
        v66 = v61.get('qos', _MISSING)
        if v66 is not _MISSING:
            if not type(v66) is dict:
                return False
            if not v66.keys() <= _C9:
                return False
            v67 = v66.get('reliability', _MISSING)
            if v67 is not _MISSING:
                if not (type(v67) is str and v67 in _C10):
                    return False
            v68 = v66.get('durability', _MISSING)
            if v68 is not _MISSING:
                if not (type(v68) is str and v68 in _C11):
                    return False
            v69 = v66.get('deadline', _MISSING)
            if v69 is not _MISSING:
                if not (type(v69) in _NUMBER or v69 is None):
                    return False
                if type(v69) in _NUMBER and v69 <= 0:
                    return False
            v70 = v66.get('liveliness', _MISSING)
            if v70 is not _MISSING:
                if not (type(v70) is str and v70 in _C12):
                    return False
            v71 = v66.get('lease_duration', _MISSING)
            if v71 is not _MISSING:
                if not (type(v71) in _NUMBER or v71 is None):
                    return False
                if type(v71) in _NUMBER and v71 <= 0:
                    return False
            v72 = v66.get('depth', _MISSING)
            if v72 is not _MISSING:
                if not (type(v72) is int or (type(v72) is float and v72.is_integer())):
                    return False
                if v72 < 0:
                    return False
    return True


def _branch2(data):
    if not type(data) is dict:
        return False
    if not data.keys() <= _C17:
        return False
    v89 = data.get('substitution', _MISSING)
    if v89 is _MISSING:
        return False
    if not type(v89) is str:
        return False
    if len(v89) < 1:
        return False
    return True


def validate(data):
    if not type(data) is dict:
        return False
    if not data.keys() <= _C0:
        return False
    v1 = data.get('format', _MISSING)
    if v1 is _MISSING:
        return False
    if not (type(v1) is str and v1 == 'rosreconf/component-library'):
        return False
    v2 = data.get('version', _MISSING)
    if v2 is _MISSING:
        return False
    if not (type(v2) in _NUMBER and v2 == 1):
        return False
    v3 = data.get('name', _MISSING)
    if v3 is _MISSING:
        return False
    if not type(v3) is str:
        return False
    if v3 not in _C2:
        if _C1(v3) is None:
            return False
        if len(_C2) < 100000:
            _C2.add(v3)
    v4 = data.get('description', _MISSING)
    if v4 is not _MISSING:
        if not type(v4) is str:
            return False
    v5 = data.get('components', _MISSING)
    if v5 is _MISSING:
        return False
    if not type(v5) is list:
        return False
    if len(v5) < 1:
        return False
    for v6 in v5:
        if not type(v6) is dict:
            return False
        if not v6.keys() <= _C3:
            return False
        v7 = v6.get('name', _MISSING)
        if v7 is _MISSING:
            return False
        if not type(v7) is str:
            return False
        if v7 not in _C2:
            if _C1(v7) is None:
                return False
            if len(_C2) < 100000:
                _C2.add(v7)
        v8 = v6.get('abstraction', _MISSING)
        if v8 is _MISSING:
            return False
        if not type(v8) is str:
            return False
        if v8 not in _C2:
            if _C1(v8) is None:
                return False
            if len(_C2) < 100000:
                _C2.add(v8)
        v9 = v6.get('description', _MISSING)
        if v9 is not _MISSING:
            if not type(v9) is str:
                return False
        v10 = v6.get('provides', _MISSING)
        if v10 is not _MISSING:
            if not type(v10) is list:
                return False
            for v11 in v10:
                if not type(v11) is dict:
                    return False
                if ((not ('topic' not in v11)) + (not ('service' not in v11)) + (not ('action' not in v11))) != 1:
                    return False
                if not v11.keys() <= _C4:
                    return False
                v12 = v11.get('topic', _MISSING)
                if v12 is not _MISSING:
                    if not type(v12) is str:
                        return False
                    if v12 not in _C6:
                        if _C5(v12) is None:
                            return False
                        if len(_C6) < 100000:
                            _C6.add(v12)
                v13 = v11.get('service', _MISSING)
                if v13 is not _MISSING:
                    if not type(v13) is str:
                        return False
                    if v13 not in _C6:
                        if _C5(v13) is None:
                            return False
                        if len(_C6) < 100000:
                            _C6.add(v13)
                v14 = v11.get('action', _MISSING)
                if v14 is not _MISSING:
                    if not type(v14) is str:
                        return False
                    if v14 not in _C6:
                        if _C5(v14) is None:
                            return False
                        if len(_C6) < 100000:
                            _C6.add(v14)
                v15 = v11.get('type', _MISSING)
                if v15 is _MISSING:
                    return False
                if not type(v15) is str:
                    return False
                if v15 not in _C8:
                    if _C7(v15) is None:
                        return False
                    if len(_C8) < 100000:
                        _C8.add(v15)
                v16 = v11.get('qos', _MISSING)
                if v16 is not _MISSING:
                    if not type(v16) is dict:
                        return False
                    if not v16.keys() <= _C9:
                        return False
                    v17 = v16.get('reliability', _MISSING)
                    if v17 is not _MISSING:
                        if not (type(v17) is str and v17 in _C10):
                            return False
                    v18 = v16.get('durability', _MISSING)
                    if v18 is not _MISSING:
                        if not (type(v18) is str and v18 in _C11):
                            return False
                    v19 = v16.get('deadline', _MISSING)
                    if v19 is not _MISSING:
                        if not (type(v19) in _NUMBER or v19 is None):
                            return False
                        if type(v19) in _NUMBER and v19 <= 0:
                            return False
                    v20 = v16.get('liveliness', _MISSING)
                    if v20 is not _MISSING:
                        if not (type(v20) is str and v20 in _C12):
                            return False
                    v21 = v16.get('lease_duration', _MISSING)
                    if v21 is not _MISSING:
                        if not (type(v21) in _NUMBER or v21 is None):
                            return False
                        if type(v21) in _NUMBER and v21 <= 0:
                            return False
                    v22 = v16.get('depth', _MISSING)
                    if v22 is not _MISSING:
                        if not (type(v22) is int or (type(v22) is float and v22.is_integer())):
                            return False
                        if v22 < 0:
                            return False
        v23 = v6.get('requires', _MISSING)
        if v23 is not _MISSING:
            if not type(v23) is list:
                return False
            for v24 in v23:
                if (_branch0(v24) + _branch1(v24)) != 1:
                    return False
        v73 = v6.get('failure_probability', _MISSING)
        if v73 is not _MISSING:
            if not type(v73) in _NUMBER:
                return False
            if v73 < 0:
                return False
            if v73 > 1:
                return False
        v74 = v6.get('needs', _MISSING)
        if v74 is not _MISSING:
            if not type(v74) is list:
                return False
            for v75 in v74:
                if not type(v75) is str:
                    return False
                if v75 not in _C2:
                    if _C1(v75) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v75)
            if len(set(v74)) != len(v74):
                return False
        v76 = v6.get('excludes', _MISSING)
        if v76 is not _MISSING:
            if not type(v76) is list:
                return False
            for v77 in v76:
                if not type(v77) is str:
                    return False
                if v77 not in _C2:
                    if _C1(v77) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v77)
            if len(set(v76)) != len(v76):
                return False
        v78 = v6.get('schemas', _MISSING)
        if v78 is not _MISSING:
            if not type(v78) is list:
                return False
            for v79 in v78:
                if not type(v79) is str:
                    return False
                if v79 not in _C2:
                    if _C1(v79) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v79)
            if len(set(v78)) != len(v78):
                return False
        v80 = v6.get('ros', _MISSING)
        if v80 is not _MISSING:
            if not type(v80) is dict:
                return False
            if not v80.keys() <= _C14:
                return False
            v81 = v80.get('package', _MISSING)
            if v81 is _MISSING:
                return False
            if not type(v81) is str:
                return False
            if v81 not in _C2:
                if _C1(v81) is None:
                    return False
                if len(_C2) < 100000:
                    _C2.add(v81)
            v82 = v80.get('executable', _MISSING)
            if v82 is _MISSING:
                return False
            if not type(v82) is str:
                return False
            if v82 not in _C16:
                if _C15(v82) is None:
                    return False
                if len(_C16) < 100000:
                    _C16.add(v82)
            v83 = v80.get('namespace', _MISSING)
            if v83 is not _MISSING:
                if not type(v83) is str:
                    return False
                if v83 not in _C6:
                    if _C5(v83) is None:
                        return False
                    if len(_C6) < 100000:
                        _C6.add(v83)
            v84 = v80.get('node', _MISSING)
            if v84 is not _MISSING:
                if not type(v84) is str:
                    return False
                if v84 not in _C2:
                    if _C1(v84) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v84)
            v85 = v80.get('parameters', _MISSING)
            if v85 is not _MISSING:
                if not type(v85) is dict:
                    return False
                for v87 in v85.values():
                    if ((not (not (type(v87) is str or type(v87) in _NUMBER or type(v87) is bool))) + _branch2(v87)) != 1:
                        return False
                for v90 in v85:
                    if not type(v90) is str:
                        return False
                    if v90 not in _C2:
                        if _C1(v90) is None:
                            return False
                        if len(_C2) < 100000:
                            _C2.add(v90)
            v91 = v80.get('remappings', _MISSING)
            if v91 is not _MISSING:
                if not type(v91) is dict:
                    return False
                for v93 in v91.values():
                    if not type(v93) is str:
                        return False
                    if v93 not in _C6:
                        if _C5(v93) is None:
                            return False
                        if len(_C6) < 100000:
                            _C6.add(v93)
                for v94 in v91:
                    if not type(v94) is str:
                        return False
                    if v94 not in _C6:
                        if _C5(v94) is None:
                            return False
                        if len(_C6) < 100000:
                            _C6.add(v94)
            v95 = v80.get('lifecycle', _MISSING)
            if v95 is not _MISSING:
                if not type(v95) is bool:
                    return False
            v96 = v80.get('args', _MISSING)
            if v96 is not _MISSING:
                if not type(v96) is list:
                    return False
                for v97 in v96:
                    if not type(v97) is str:
                        return False
        v98 = v6.get('metrics', _MISSING)
        if v98 is not _MISSING:
            if not type(v98) is dict:
                return False
            for v100 in v98.values():
                if not type(v100) in _NUMBER:
                    return False
            for v101 in v98:
                if not type(v101) is str:
                    return False
                if v101 not in _C2:
                    if _C1(v101) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v101)
        v102 = v6.get('dynamics', _MISSING)
        if v102 is not _MISSING:
            if not type(v102) is dict:
                return False
            if ((not ('transfer_function' not in v102)) + (not ('state_space' not in v102))) != 1:
                return False
            if not v102.keys() <= _C18:
                return False
            v103 = v102.get('transfer_function', _MISSING)
            if v103 is not _MISSING:
                if not type(v103) is dict:
                    return False
                if not v103.keys() <= _C19:
                    return False
                v104 = v103.get('num', _MISSING)
                if v104 is _MISSING:
                    return False
                if not type(v104) is list:
                    return False
                if len(v104) < 1:
                    return False
                for v105 in v104:
                    if not type(v105) in _NUMBER:
                        return False
                v106 = v103.get('den', _MISSING)
                if v106 is _MISSING:
                    return False
                if not type(v106) is list:
                    return False
                if len(v106) < 1:
                    return False
                for v107 in v106:
                    if not type(v107) in _NUMBER:
                        return False
            v108 = v102.get('state_space', _MISSING)
            if v108 is not _MISSING:
                if not type(v108) is dict:
                    return False
                if not v108.keys() <= _C20:
                    return False
                v109 = v108.get('A', _MISSING)
                if v109 is _MISSING:
                    return False
                if not type(v109) is list:
                    return False
                if len(v109) < 1:
                    return False
                for v110 in v109:
                    if not type(v110) is list:
                        return False
                    if len(v110) < 1:
                        return False
                    for v111 in v110:
                        if not type(v111) in _NUMBER:
                            return False
                v112 = v108.get('B', _MISSING)
                if v112 is _MISSING:
                    return False
                if not type(v112) is list:
                    return False
                if len(v112) < 1:
                    return False
                for v113 in v112:
                    if not type(v113) is list:
                        return False
                    if len(v113) < 1:
                        return False
                    for v114 in v113:
                        if not type(v114) in _NUMBER:
                            return False
                v115 = v108.get('C', _MISSING)
                if v115 is _MISSING:
                    return False
                if not type(v115) is list:
                    return False
                if len(v115) < 1:
                    return False
                for v116 in v115:
                    if not type(v116) is list:
                        return False
                    if len(v116) < 1:
                        return False
                    for v117 in v116:
                        if not type(v117) in _NUMBER:
                            return False
                v118 = v108.get('D', _MISSING)
                if v118 is _MISSING:
                    return False
                if not type(v118) is list:
                    return False
                if len(v118) < 1:
                    return False
                for v119 in v118:
                    if not type(v119) is list:
                        return False
                    if len(v119) < 1:
                        return False
                    for v120 in v119:
                        if not type(v120) in _NUMBER:
                            return False
            v121 = v102.get('delay', _MISSING)
            if v121 is not _MISSING:
                if not type(v121) in _NUMBER:
                    return False
                if v121 < 0:
                    return False
    return True


VALIDATE = validate

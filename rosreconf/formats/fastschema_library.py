"""The verdict of component-library.schema.json as code: written by
scripts/fast_validators.py, do not edit (see structure.fast_validator).
"""

# ruff: noqa
# fmt: off
# mypy: ignore-errors
SOURCE = '7fe5490eac7c9f8a86b76bd69736c4e82258927dfeb3fa6c626f3c3de0422356'
import re

_NUMBER = (int, float)
_MISSING = object()
_C0 = frozenset({'components', 'description', 'format', 'name', 'version'})
_C1 = re.compile('^[A-Za-z][A-Za-z0-9_]*$').search
_C2 = set()  # texts _C1 matched
_C3 = frozenset({'abstraction', 'description', 'dynamics', 'excludes', 'failure_probability', 'metrics', 'name', 'needs', 'provides', 'requires', 'ros', 'schemas'})
_C4 = frozenset({'qos', 'service', 'topic', 'type'})
_C5 = re.compile('^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*$').search
_C6 = set()  # texts _C5 matched
_C7 = re.compile('^[A-Za-z][A-Za-z0-9_]*/[A-Za-z][A-Za-z0-9_]*$').search
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
    if ((not ('topic' not in data)) + (not ('service' not in data))) != 1:
        return False
    if not data.keys() <= _C4:
        return False
    v34 = data.get('topic', _MISSING)
    if v34 is not _MISSING:
        if not type(v34) is str:
            return False
        if v34 not in _C6:
            if _C5(v34) is None:
                return False
            if len(_C6) < 100000:
                _C6.add(v34)
    v35 = data.get('service', _MISSING)
    if v35 is not _MISSING:
        if not type(v35) is str:
            return False
        if v35 not in _C6:
            if _C5(v35) is None:
                return False
            if len(_C6) < 100000:
                _C6.add(v35)
    v36 = data.get('type', _MISSING)
    if v36 is _MISSING:
        return False
    if not type(v36) is str:
        return False
    if v36 not in _C8:
        if _C7(v36) is None:
            return False
        if len(_C8) < 100000:
            _C8.add(v36)
    v37 = data.get('qos', _MISSING)
    if v37 is not _MISSING:
        if not type(v37) is dict:
            return False
        if not v37.keys() <= _C9:
            return False
        v38 = v37.get('reliability', _MISSING)
        if v38 is not _MISSING:
            if not (type(v38) is str and v38 in _C10):
                return False
        v39 = v37.get('durability', _MISSING)
        if v39 is not _MISSING:
            if not (type(v39) is str and v39 in _C11):
                return False
        v40 = v37.get('deadline', _MISSING)
        if v40 is not _MISSING:
            if not (type(v40) in _NUMBER or v40 is None):
                return False
            if type(v40) in _NUMBER and v40 <= 0:
                return False
        v41 = v37.get('liveliness', _MISSING)
        if v41 is not _MISSING:
            if not (type(v41) is str and v41 in _C12):
                return False
        v42 = v37.get('lease_duration', _MISSING)
        if v42 is not _MISSING:
            if not (type(v42) in _NUMBER or v42 is None):
                return False
            if type(v42) in _NUMBER and v42 <= 0:
                return False
        v43 = v37.get('depth', _MISSING)
        if v43 is not _MISSING:
            if not (type(v43) is int or (type(v43) is float and v43.is_integer())):
                return False
            if v43 < 0:
                return False
    return True


def _branch1(data):
    if not type(data) is dict:
        return False
    if not data.keys() <= _C13:
        return False
    v56 = data.get('any_of', _MISSING)
    if v56 is _MISSING:
        return False
    if not type(v56) is list:
        return False
    if len(v56) < 2:
        return False
    for v57 in v56:
        if not type(v57) is dict:
            return False
        if ((not ('topic' not in v57)) + (not ('service' not in v57))) != 1:
            return False
        if not v57.keys() <= _C4:
            return False
        v58 = v57.get('topic', _MISSING)
        if v58 is not _MISSING:
            if not type(v58) is str:
                return False
            if v58 not in _C6:
                if _C5(v58) is None:
                    return False
                if len(_C6) < 100000:
                    _C6.add(v58)
        v59 = v57.get('service', _MISSING)
        if v59 is not _MISSING:
            if not type(v59) is str:
                return False
            if v59 not in _C6:
                if _C5(v59) is None:
                    return False
                if len(_C6) < 100000:
                    _C6.add(v59)
        v60 = v57.get('type', _MISSING)
        if v60 is _MISSING:
            return False
        if not type(v60) is str:
            return False
        if v60 not in _C8:
            if _C7(v60) is None:
                return False
            if len(_C8) < 100000:
                _C8.add(v60)
        v61 = v57.get('qos', _MISSING)
        if v61 is not _MISSING:
            if not type(v61) is dict:
                return False
            if not v61.keys() <= _C9:
                return False
            v62 = v61.get('reliability', _MISSING)
            if v62 is not _MISSING:
                if not (type(v62) is str and v62 in _C10):
                    return False
            v63 = v61.get('durability', _MISSING)
            if v63 is not _MISSING:
                if not (type(v63) is str and v63 in _C11):
                    return False
            v64 = v61.get('deadline', _MISSING)
            if v64 is not _MISSING:
                if not (type(v64) in _NUMBER or v64 is None):
                    return False
                if type(v64) in _NUMBER and v64 <= 0:
                    return False
            v65 = v61.get('liveliness', _MISSING)
            if v65 is not _MISSING:
                if not (type(v65) is str and v65 in _C12):
                    return False
            v66 = v61.get('lease_duration', _MISSING)
            if v66 is not _MISSING:
                if not (type(v66) in _NUMBER or v66 is None):
                    return False
                if type(v66) in _NUMBER and v66 <= 0:
                    return False
            v67 = v61.get('depth', _MISSING)
            if v67 is not _MISSING:
                if not (type(v67) is int or (type(v67) is float and v67.is_integer())):
                    return False
                if v67 < 0:
                    return False
    return True


def _branch2(data):
    if not type(data) is dict:
        return False
    if not data.keys() <= _C17:
        return False
    v84 = data.get('substitution', _MISSING)
    if v84 is _MISSING:
        return False
    if not type(v84) is str:
        return False
    if len(v84) < 1:
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
                if ((not ('topic' not in v11)) + (not ('service' not in v11))) != 1:
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
                v14 = v11.get('type', _MISSING)
                if v14 is _MISSING:
                    return False
                if not type(v14) is str:
                    return False
                if v14 not in _C8:
                    if _C7(v14) is None:
                        return False
                    if len(_C8) < 100000:
                        _C8.add(v14)
                v15 = v11.get('qos', _MISSING)
                if v15 is not _MISSING:
                    if not type(v15) is dict:
                        return False
                    if not v15.keys() <= _C9:
                        return False
                    v16 = v15.get('reliability', _MISSING)
                    if v16 is not _MISSING:
                        if not (type(v16) is str and v16 in _C10):
                            return False
                    v17 = v15.get('durability', _MISSING)
                    if v17 is not _MISSING:
                        if not (type(v17) is str and v17 in _C11):
                            return False
                    v18 = v15.get('deadline', _MISSING)
                    if v18 is not _MISSING:
                        if not (type(v18) in _NUMBER or v18 is None):
                            return False
                        if type(v18) in _NUMBER and v18 <= 0:
                            return False
                    v19 = v15.get('liveliness', _MISSING)
                    if v19 is not _MISSING:
                        if not (type(v19) is str and v19 in _C12):
                            return False
                    v20 = v15.get('lease_duration', _MISSING)
                    if v20 is not _MISSING:
                        if not (type(v20) in _NUMBER or v20 is None):
                            return False
                        if type(v20) in _NUMBER and v20 <= 0:
                            return False
                    v21 = v15.get('depth', _MISSING)
                    if v21 is not _MISSING:
                        if not (type(v21) is int or (type(v21) is float and v21.is_integer())):
                            return False
                        if v21 < 0:
                            return False
        v22 = v6.get('requires', _MISSING)
        if v22 is not _MISSING:
            if not type(v22) is list:
                return False
            for v23 in v22:
                if (_branch0(v23) + _branch1(v23)) != 1:
                    return False
        v68 = v6.get('failure_probability', _MISSING)
        if v68 is not _MISSING:
            if not type(v68) in _NUMBER:
                return False
            if v68 < 0:
                return False
            if v68 > 1:
                return False
        v69 = v6.get('needs', _MISSING)
        if v69 is not _MISSING:
            if not type(v69) is list:
                return False
            for v70 in v69:
                if not type(v70) is str:
                    return False
                if v70 not in _C2:
                    if _C1(v70) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v70)
            if len(set(v69)) != len(v69):
                return False
        v71 = v6.get('excludes', _MISSING)
        if v71 is not _MISSING:
            if not type(v71) is list:
                return False
            for v72 in v71:
                if not type(v72) is str:
                    return False
                if v72 not in _C2:
                    if _C1(v72) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v72)
            if len(set(v71)) != len(v71):
                return False
        v73 = v6.get('schemas', _MISSING)
        if v73 is not _MISSING:
            if not type(v73) is list:
                return False
            for v74 in v73:
                if not type(v74) is str:
                    return False
                if v74 not in _C2:
                    if _C1(v74) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v74)
            if len(set(v73)) != len(v73):
                return False
        v75 = v6.get('ros', _MISSING)
        if v75 is not _MISSING:
            if not type(v75) is dict:
                return False
            if not v75.keys() <= _C14:
                return False
            v76 = v75.get('package', _MISSING)
            if v76 is _MISSING:
                return False
            if not type(v76) is str:
                return False
            if v76 not in _C2:
                if _C1(v76) is None:
                    return False
                if len(_C2) < 100000:
                    _C2.add(v76)
            v77 = v75.get('executable', _MISSING)
            if v77 is _MISSING:
                return False
            if not type(v77) is str:
                return False
            if v77 not in _C16:
                if _C15(v77) is None:
                    return False
                if len(_C16) < 100000:
                    _C16.add(v77)
            v78 = v75.get('namespace', _MISSING)
            if v78 is not _MISSING:
                if not type(v78) is str:
                    return False
                if v78 not in _C6:
                    if _C5(v78) is None:
                        return False
                    if len(_C6) < 100000:
                        _C6.add(v78)
            v79 = v75.get('node', _MISSING)
            if v79 is not _MISSING:
                if not type(v79) is str:
                    return False
                if v79 not in _C2:
                    if _C1(v79) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v79)
            v80 = v75.get('parameters', _MISSING)
            if v80 is not _MISSING:
                if not type(v80) is dict:
                    return False
                for v82 in v80.values():
                    if ((not (not (type(v82) is str or type(v82) in _NUMBER or type(v82) is bool))) + _branch2(v82)) != 1:
                        return False
                for v85 in v80:
                    if not type(v85) is str:
                        return False
                    if v85 not in _C2:
                        if _C1(v85) is None:
                            return False
                        if len(_C2) < 100000:
                            _C2.add(v85)
            v86 = v75.get('remappings', _MISSING)
            if v86 is not _MISSING:
                if not type(v86) is dict:
                    return False
                for v88 in v86.values():
                    if not type(v88) is str:
                        return False
                    if v88 not in _C6:
                        if _C5(v88) is None:
                            return False
                        if len(_C6) < 100000:
                            _C6.add(v88)
                for v89 in v86:
                    if not type(v89) is str:
                        return False
                    if v89 not in _C6:
                        if _C5(v89) is None:
                            return False
                        if len(_C6) < 100000:
                            _C6.add(v89)
            v90 = v75.get('lifecycle', _MISSING)
            if v90 is not _MISSING:
                if not type(v90) is bool:
                    return False
            v91 = v75.get('args', _MISSING)
            if v91 is not _MISSING:
                if not type(v91) is list:
                    return False
                for v92 in v91:
                    if not type(v92) is str:
                        return False
        v93 = v6.get('metrics', _MISSING)
        if v93 is not _MISSING:
            if not type(v93) is dict:
                return False
            for v95 in v93.values():
                if not type(v95) in _NUMBER:
                    return False
            for v96 in v93:
                if not type(v96) is str:
                    return False
                if v96 not in _C2:
                    if _C1(v96) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v96)
        v97 = v6.get('dynamics', _MISSING)
        if v97 is not _MISSING:
            if not type(v97) is dict:
                return False
            if ((not ('transfer_function' not in v97)) + (not ('state_space' not in v97))) != 1:
                return False
            if not v97.keys() <= _C18:
                return False
            v98 = v97.get('transfer_function', _MISSING)
            if v98 is not _MISSING:
                if not type(v98) is dict:
                    return False
                if not v98.keys() <= _C19:
                    return False
                v99 = v98.get('num', _MISSING)
                if v99 is _MISSING:
                    return False
                if not type(v99) is list:
                    return False
                if len(v99) < 1:
                    return False
                for v100 in v99:
                    if not type(v100) in _NUMBER:
                        return False
                v101 = v98.get('den', _MISSING)
                if v101 is _MISSING:
                    return False
                if not type(v101) is list:
                    return False
                if len(v101) < 1:
                    return False
                for v102 in v101:
                    if not type(v102) in _NUMBER:
                        return False
            v103 = v97.get('state_space', _MISSING)
            if v103 is not _MISSING:
                if not type(v103) is dict:
                    return False
                if not v103.keys() <= _C20:
                    return False
                v104 = v103.get('A', _MISSING)
                if v104 is _MISSING:
                    return False
                if not type(v104) is list:
                    return False
                if len(v104) < 1:
                    return False
                for v105 in v104:
                    if not type(v105) is list:
                        return False
                    if len(v105) < 1:
                        return False
                    for v106 in v105:
                        if not type(v106) in _NUMBER:
                            return False
                v107 = v103.get('B', _MISSING)
                if v107 is _MISSING:
                    return False
                if not type(v107) is list:
                    return False
                if len(v107) < 1:
                    return False
                for v108 in v107:
                    if not type(v108) is list:
                        return False
                    if len(v108) < 1:
                        return False
                    for v109 in v108:
                        if not type(v109) in _NUMBER:
                            return False
                v110 = v103.get('C', _MISSING)
                if v110 is _MISSING:
                    return False
                if not type(v110) is list:
                    return False
                if len(v110) < 1:
                    return False
                for v111 in v110:
                    if not type(v111) is list:
                        return False
                    if len(v111) < 1:
                        return False
                    for v112 in v111:
                        if not type(v112) in _NUMBER:
                            return False
                v113 = v103.get('D', _MISSING)
                if v113 is _MISSING:
                    return False
                if not type(v113) is list:
                    return False
                if len(v113) < 1:
                    return False
                for v114 in v113:
                    if not type(v114) is list:
                        return False
                    if len(v114) < 1:
                        return False
                    for v115 in v114:
                        if not type(v115) in _NUMBER:
                            return False
            v116 = v97.get('delay', _MISSING)
            if v116 is not _MISSING:
                if not type(v116) in _NUMBER:
                    return False
                if v116 < 0:
                    return False
    return True


VALIDATE = validate

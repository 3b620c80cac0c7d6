// empty_unit.cpp: gives every engine library at least one translation unit while a folder is still empty.

from server.msgs import Bool, Float64, Header, Int64, String

__all__ = ["Bool", "Float64", "Header", "Int64", "String"]
